#pragma once
// A setting's value as command-line text (cli/setting_flags.h): parse checks it against the
// setting's declaration (range, step, words) and returns what was expected ("" when it
// fits); show gives the default for the help; kind is CLI11's type name, which picks the
// tool's own checks (decimal integers, finite numbers: tool_cli.h).
#include "assetcooker/lib/cli/tool_cli.h"
#include "assetcooker/lib/settings/error_budget.h"
#include "assetcooker/lib/settings/setting.h"

#include <charconv>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>

namespace specula::cook {

// Defined for the types the command line sets; empty (no flag can set it) for the rest.
template <class T, class = void> struct SettingText {};
template <class T>
concept TextSetting = requires {
    SettingText<T>::kind();
};

// "lo .. hi" checks shared by the numbers.
std::string settingRangeCheck(double v, const SettingInfo& info);
// The index of `text` among the setting's words, or -1.
int settingWordIndex(const std::string& text, const SettingInfo& info);
std::string settingWordsExpected(const std::string& text, const SettingInfo& info);

template <class T>
struct SettingText<T, std::enable_if_t<std::is_arithmetic_v<T> && !std::is_same_v<T, bool>>> {
    static const char* kind() {
        return std::is_floating_point_v<T> ? "FLOAT" : std::is_signed_v<T> ? "INT" : "UINT";
    }
    static std::string parse(const std::string& text, const SettingInfo& info, T& v) {
        T x{};
        const auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), x);
        if (ec != std::errc() || p != text.data() + text.size() || text.empty())
            return std::string("expected ") +
                   (std::is_floating_point_v<T> ? "a number" : "an integer") + ", got '" + text +
                   "'";
        if (std::string e = settingRangeCheck(double(x), info); !e.empty()) return e;
        if constexpr (std::is_integral_v<T>)
            if (info.multipleOf > 1 && x % T(info.multipleOf) != 0)
                return "expected a multiple of " + std::to_string(info.multipleOf) + ", got '" +
                       text + "'";
        v = x;
        return {};
    }
    static std::string show(T v, const SettingInfo&) {
        std::ostringstream s;
        s << v;
        return s.str();
    }
};

// A bool, an enum or a string with words: one of them.
template <class T>
struct SettingText<T, std::enable_if_t<std::is_same_v<T, bool> || std::is_enum_v<T> ||
                                       std::is_same_v<T, std::string>>> {
    static const char* kind() { return "TEXT"; }
    static std::string parse(const std::string& text, const SettingInfo& info, T& v) {
        const int i = settingWordIndex(text, info);
        if constexpr (std::is_same_v<T, std::string>) {
            if (!info.words.empty() && i < 0) return settingWordsExpected(text, info);
            v = text;
        } else {
            if (i < 0) return settingWordsExpected(text, info);
            v = T(i);
        }
        return {};
    }
    static std::string show(const T& v, const SettingInfo& info) {
        if constexpr (std::is_same_v<T, std::string>)
            return v;
        else
            return info.words.at(std::size_t(v));
    }
};

template <class T> struct SettingText<std::optional<T>> {
    static const char* kind() { return SettingText<T>::kind(); }
    static std::string parse(const std::string& text, const SettingInfo& info,
                             std::optional<T>& v) {
        T x{};
        std::string e = SettingText<T>::parse(text, info, x);
        if (e.empty()) v = x;
        return e;
    }
    static std::string show(const std::optional<T>& v, const SettingInfo& info) {
        return v ? SettingText<T>::show(*v, info) : std::string();
    }
};

template <> struct SettingText<glm::vec3> {
    static const char* kind() { return "TEXT"; }
    static std::string parse(const std::string& text, const SettingInfo&, glm::vec3& v);
    static std::string show(const glm::vec3&, const SettingInfo&) { return {}; }
};

template <> struct SettingText<ErrorBudget> {
    static const char* kind() { return "TEXT"; }
    static std::string parse(const std::string& text, const SettingInfo& info, ErrorBudget& v);
    static std::string show(const ErrorBudget& v, const SettingInfo&) { return v.text(); }
};

template <class I> struct SettingText<ImageSizeSetting<I>> {
    static const char* kind() { return "TEXT"; }
    static std::string parse(const std::string& text, const SettingInfo&, ImageSizeSetting<I>& v) {
        int w = 0, h = 0;
        if (!cli::parseSize(text, w, h))
            return "expected WIDTHxHEIGHT, each 16..8192, got '" + text + "'";
        v.width = w, v.height = h;
        return {};
    }
    static std::string show(const ImageSizeSetting<I>& v, const SettingInfo&) {
        return std::to_string(v.width) + "x" + std::to_string(v.height);
    }
};

} // namespace specula::cook
