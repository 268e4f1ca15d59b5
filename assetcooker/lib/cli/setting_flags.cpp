#include "assetcooker/lib/cli/setting_flags.h"

#include "engine/core/error.h"

#include <algorithm>
#include <cmath>

namespace specula::cook {

namespace {

// Parses `text` as flavour S's setting `flag`: what S expected, or "" when it fits.
template <class S> std::string parseFlag(const std::string& flag, const std::string& text, S& s) {
    std::string error;
    visitSettings(s, [&](const SettingInfo& info, auto&& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (TextSetting<T>)
            if (info.flag && flag == info.flag) error = SettingText<T>::parse(text, info, v);
    });
    return error;
}

// The flag's check for flavour S when parsed (a scratch settings value takes it).
template <class S> auto checkFor(const std::string& flag) {
    return [flag](const std::string& text) {
        S scratch{};
        return parseFlag(flag, text, scratch);
    };
}

std::string joined(const std::vector<std::string>& words, const char* sep, const char* last) {
    std::string out;
    for (std::size_t i = 0; i < words.size(); ++i)
        out += (i == 0 ? "" : i + 1 == words.size() ? last : sep) + words[i];
    return out;
}

// What the setting accepts, for its help: " {a|b}", " [1 .. 4096]", " [4 .. 4096, multiple
// of 4]"; "" when anything of its type goes.
std::string accepted(const SettingInfo& info) {
    std::vector<std::string> words(info.words.begin(), info.words.end());
    if (!words.empty()) return " {" + joined(words, "|", "|") + "}";
    if (!std::isfinite(info.lo) && !std::isfinite(info.hi)) return "";
    return " [" + settingRange(info) +
           (info.multipleOf > 1 ? ", multiple of " + std::to_string(info.multipleOf) : "") + "]";
}

} // namespace

void SettingFlags::add(cli::ToolCli& tool, CLI::App* sub, const std::string& flavour,
                       const std::vector<std::string>& only) {
    // Every flag each flavour declares, with its help and its default in that flavour.
    std::map<std::string, std::vector<std::function<std::string(const std::string&)>>> checks;
    forEachCookFlavour([&](const auto& defaults) {
        using S = std::decay_t<decltype(defaults)>;
        if (!flavour.empty() && flavour != S::kFlavour) return;
        visitSettings(defaults, [&](const SettingInfo& info, const auto& v) {
            using T = std::decay_t<decltype(v)>;
            if (!info.flag || (!only.empty() && std::find(only.begin(), only.end(),
                                                          std::string(info.flag)) == only.end()))
                return;
            if (info.key) tool.mapField(info.key, info.flag);
            if constexpr (TextSetting<T>) {
                Flag& f = flags_[info.flag];
                const std::string shown = SettingText<T>::show(v, info);
                f.flavours.push_back(S::kFlavour);
                f.helps.push_back(info.help + accepted(info) +
                                  (shown.empty() ? "" : " (default " + shown + ")"));
                f.kind = SettingText<T>::kind();
                checks[info.flag].push_back(checkFor<S>(info.flag));
            }
        });
    });
    for (auto& [name, f] : flags_) {
        std::string help;
        if (f.flavours.size() == 1) {
            help = f.helps.front();
        } else {
            std::vector<std::string> parts;
            for (std::size_t i = 0; i < f.flavours.size(); ++i)
                parts.push_back(f.flavours[i] + ": " + f.helps[i]);
            help = joined(parts, "; ", "; ");
        }
        f.option = sub->add_option(name, f.text, help)->type_name(f.kind);
        f.option->group(joined(f.flavours, "/", "/") + " options");
        // Some flavour must take the value (which one the flag was meant for is known only
        // once --flavour is read); settings() then checks it against the chosen one.
        f.option->check(CLI::Validator(
            [fs = checks[name]](std::string& text) -> std::string {
                std::string first;
                for (const auto& check : fs) {
                    std::string e = check(text);
                    if (e.empty()) return {};
                    if (first.empty()) first = e;
                }
                return first;
            },
            ""));
    }
}

bool SettingFlags::given(const std::string& flag) const {
    const auto it = flags_.find(flag);
    return it != flags_.end() && it->second.option && it->second.option->count() > 0;
}

CookFlavour SettingFlags::settings(const std::string& flavour, const std::string& file) const {
    std::optional<CookFlavour> out;
    forEachCookFlavour([&](const auto& defaults) {
        using S = std::decay_t<decltype(defaults)>;
        if (flavour != S::kFlavour) return;
        S s = defaults;
        for (const auto& [name, f] : flags_) {
            if (!given(name)) continue;
            if (std::find(f.flavours.begin(), f.flavours.end(), flavour) == f.flavours.end())
                throw UsageError(name, "applies to --flavour " + joined(f.flavours, "|", "|") +
                                           " only, not to --flavour " + flavour);
            if (std::string e = parseFlag(name, f.text, s); !e.empty())
                throw UsageError(name, e + " (--flavour " + flavour + ")");
        }
        try {
            checkCookSettings(s, file);
        } catch (const Error& e) {
            throw UsageError(e.field(), e.message()); // the tool names the field's flag
        }
        out = s;
    });
    if (!out)
        throw UsageError("--flavour", "expected " + cookFlavourList() + ", got '" + flavour + "'");
    return *out;
}

} // namespace specula::cook
