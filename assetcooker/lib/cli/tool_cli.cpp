#include "assetcooker/lib/cli/tool_cli.h"

#include "engine/core/error.h"
#include "engine/core/regular_file.h"
#include "specula/version.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <exception>
#include <optional>
#include <sstream>
#include <vector>

namespace specula::cli {

namespace {

std::string firstLine(const std::string& s) {
    return s.substr(0, s.find('\n'));
}

std::optional<double> finiteNumber(const std::string& text) {
    double v = 0.0;
    const char* end = text.data() + text.size();
    const auto [p, ec] = std::from_chars(text.data(), end, v);
    if (ec != std::errc() || p != end || !std::isfinite(v)) return std::nullopt;
    return v;
}

std::string rangeText(double lo, double hi) {
    std::ostringstream s;
    s << "[" << lo << ", " << hi << "]";
    return s.str();
}

// The first positional of a subcommand, e.g. SCENE; empty when it takes none.
std::string positionalName(const CLI::App* sub) {
    for (const CLI::Option* o : sub->get_options())
        if (o->get_positional()) return o->get_name();
    return {};
}

// What an argument nobody consumed was, in the words of the subcommand it was given to.
std::string unexpected(const std::string& arg, const CLI::App* sub) {
    if (arg.size() > 1 && arg[0] == '-') return "unknown option '" + arg + "'";
    if (!sub) return "unknown subcommand '" + arg + "' (try --help)";
    const std::string pos = positionalName(sub);
    if (pos.empty()) return sub->get_name() + " takes no positional argument, got '" + arg + "'";
    return sub->get_name() + " takes exactly one " + pos + ", got also '" + arg + "'";
}

// A config file larger than this is no config file.
constexpr std::uint64_t kMaxConfigBytes = 1 << 20;

// What CLI11 calls the option's type ("INT", "UINT", "FLOAT", "TEXT", ...), without the
// validators' descriptions it appends after ':'.
std::string valueKind(const CLI::Option& option) {
    const std::string name = option.get_type_name();
    return name.substr(0, name.find(':'));
}

// The check every value of `kind` gets before the option's own validators.
CLI::Validator valueCheck(const std::string& kind, bool emptyAllowed) {
    if (kind == "INT" || kind == "UINT") return decimalInteger(kind == "INT");
    const bool number = kind == "FLOAT";
    return CLI::Validator(
        [number, emptyAllowed](std::string& text) -> std::string {
            if (text.empty())
                return emptyAllowed && !number ? std::string() : "expected a value, got ''";
            if (number && !finiteNumber(text))
                return "expected a finite decimal number, got '" + text + "'";
            return {};
        },
        "");
}

} // namespace

ToolCli::ToolCli(std::string tool, std::string description)
    : app_(std::move(description), std::move(tool)) {
    app_.get_formatter()->label("Usage", "usage");
    app_.get_formatter()->column_width(26);
    app_.set_help_flag("-h,--help", "show this help");
    app_.set_version_flag("--version", app_.get_name() + " " + SPECULA_VERSION,
                          "print the version and exit");
    app_.option_defaults()->always_capture_default();
    app_.set_config("--config", "",
                    "read options from FILE (TOML or INI, one [section] per subcommand, e.g. "
                    "[bake] face-res = 64); flags on the command line win")
        ->type_name("FILE");
    app_.allow_config_extras(CLI::config_extras_mode::error);
    app_.footer("\nValues, on the command line and in --config alike: integers are decimal (010 is "
                "ten,\nnever octal), numbers finite (no nan or inf), and none may be empty unless "
                "its\nflag says so (--sky '').");
    app_.require_subcommand(0, 1);
    // Inherited by every subcommand: its unknown arguments (and --config after the
    // subcommand name) reach the tool, which names them in its own words.
    app_.allow_extras();
    app_.fallthrough();
}

CLI::App* ToolCli::addSubcommand(const std::string& name, const std::string& summary,
                                 const std::string& description, const std::string& footer,
                                 Action run) {
    CLI::App* sub = app_.add_subcommand(name, summary);
    // The summary is its line in the tool's help and the first line of its own; the longer
    // description follows the generated option list.
    sub->footer("\n" + description + (footer.empty() ? "" : "\n" + footer));
    actions_[sub] = std::move(run);
    return sub;
}

void ToolCli::checkValues() {
    if (valuesChecked_) return;
    valuesChecked_ = true;
    std::vector<CLI::App*> apps = app_.get_subcommands([](CLI::App*) { return true; });
    apps.push_back(&app_);
    CLI::Option* config = app_.get_config_ptr();
    for (CLI::App* app : apps)
        for (CLI::Option* option : app->get_options()) {
            if (option->get_type_size_max() == 0) continue; // a flag takes no value
            if (option == config) continue;
            // A transform goes before the validators the subcommand added: they see the
            // decimal text (CLI11 would read "010" as octal), never an empty or NaN value.
            option->transform(valueCheck(valueKind(*option), emptyAllowed_.count(option) > 0));
        }
    // CLI11 reads anything that is not a folder, and waits forever on a FIFO.
    config->check(CLI::Validator(
        [](std::string& path) -> std::string {
            if (path.empty()) return "expected a file, got ''";
            try {
                (void)regularFileSize(path, kMaxConfigBytes);
                return {};
            } catch (const Error& e) {
                return e.what();
            }
        },
        ""));
}

int ToolCli::dispatch(std::span<const std::string> args, std::ostream& out) {
    checkValues();
    std::vector<std::string> reversed(args.rbegin(), args.rend()); // CLI11 pops from the back
    app_.parse(reversed);
    const std::vector<CLI::App*> chosen = app_.get_subcommands();
    const CLI::App* sub = chosen.empty() ? nullptr : chosen.front();
    const std::vector<std::string> extra = app_.remaining(true);
    if (!extra.empty()) throw UsageError(unexpected(extra.front(), sub));
    if (!sub) throw UsageError("missing subcommand (try --help)");
    return actions_.at(sub)(out);
}

std::string ToolCli::describe(const std::exception& e) const {
    const std::string what = firstLine(e.what());
    const auto* error = dynamic_cast<const Error*>(&e);
    if (!error || !error->file().empty()) return what;
    const auto flag = fieldFlags_.find(error->field());
    return flag == fieldFlags_.end() ? what : flag->second + what.substr(error->field().size());
}

int ToolCli::run(std::span<const std::string> args, std::ostream& out, std::ostream& err) {
    auto where = [&] {
        const std::vector<CLI::App*> chosen = app_.get_subcommands();
        return chosen.empty() ? app_.get_name() : app_.get_name() + " " + chosen[0]->get_name();
    };
    auto usageError = [&](const std::string& message) {
        err << "usage: " << where() << " --help\n" << where() << ": error: " << message << '\n';
        return kExitUsage;
    };
    // What the subcommand printed must have reached its reader: a full disk or a closed
    // pipe is an error, never an exit 0 with a truncated or empty output.
    auto written = [&](int status) {
        errno = 0;
        out.flush();
        if (!out.fail() || status != kExitOk) return status;
        const int error = errno;
        err << where() << ": error: cannot write to standard output"
            << (error ? std::string(": ") + std::strerror(error) : std::string()) << '\n';
        return kExitFailure;
    };
    try {
        return written(dispatch(args, out));
    } catch (const CLI::CallForVersion& e) {
        out << e.what() << '\n';
        return written(kExitOk);
    } catch (const CLI::CallForHelp&) {
        out << app_.help();
        return written(kExitOk);
    } catch (const CLI::FileError& e) {
        return usageError("--config: " + firstLine(e.what()));
    } catch (const CLI::ConfigError& e) {
        return usageError("--config: " + firstLine(e.what()));
    } catch (const CLI::ParseError& e) {
        return usageError(firstLine(e.what()));
    } catch (const UsageError& e) {
        return usageError(describe(e)); // a library field raised as usage names its flag
    } catch (const Cancelled& e) {
        err << where() << ": cancelled: " << firstLine(e.what()) << '\n';
        return kExitCancelled;
    } catch (const std::exception& e) {
        err << where() << ": error: " << describe(e) << '\n';
    }
    return kExitFailure;
}

CLI::Validator finiteRange(double lo, double hi) {
    return CLI::Validator(
        [lo, hi](std::string& text) -> std::string {
            const auto v = finiteNumber(text);
            if (v && *v >= lo && *v <= hi) return {};
            return "expected a number in " + rangeText(lo, hi) + ", got '" + text + "'";
        },
        rangeText(lo, hi));
}

CLI::Validator nonEmpty(const std::string& what) {
    return CLI::Validator(
        [what](std::string& text) -> std::string {
            return text.empty() ? "expected " + what + ", got ''" : std::string();
        },
        "");
}

CLI::Validator decimalInteger(bool isSigned) {
    return CLI::Validator(
        [isSigned](std::string& text) -> std::string {
            const std::size_t sign = isSigned && !text.empty() && text[0] == '-' ? 1 : 0;
            const std::string digits = text.substr(sign);
            if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos)
                return std::string(isSigned ? "expected a decimal integer"
                                            : "expected a decimal integer >= 0") +
                       ", got '" + text + "'";
            std::string decimal =
                digits.substr(std::min(digits.find_first_not_of('0'), digits.size() - 1));
            if (sign && decimal != "0") decimal.insert(0, "-");
            std::int64_t v = 0;
            std::uint64_t u = 0;
            const char* end = decimal.data() + decimal.size();
            const std::errc ec = isSigned ? std::from_chars(decimal.data(), end, v).ec
                                          : std::from_chars(decimal.data(), end, u).ec;
            if (ec != std::errc()) return "out of range, got '" + text + "'";
            text = decimal;
            return {};
        },
        "");
}

glm::vec3 parseVec3(const std::string& text) {
    glm::vec3 v(0.f);
    std::size_t start = 0;
    for (int i = 0; i < 3; ++i) {
        const std::size_t comma = text.find(',', start);
        const auto x = finiteNumber(text.substr(start, comma - start));
        if ((i < 2) != (comma != std::string::npos) || !x || std::abs(*x) > 1e7)
            throw UsageError("expected x,y,z (finite numbers up to 1e7), got '" + text + "'");
        v[i] = float(*x);
        start = comma + 1;
    }
    return v;
}

CLI::Validator vec3Text() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            try {
                parseVec3(text);
                return {};
            } catch (const UsageError& e) {
                return e.what();
            }
        },
        "x,y,z");
}

bool parseSize(const std::string& text, int& width, int& height) {
    const std::size_t x = text.find('x');
    if (x == std::string::npos) return false;
    // Decimal sides (CLI11's lexical_cast would read "0100" as octal 64).
    const auto side = [&](std::size_t from, std::size_t to, int& v) {
        const auto [p, ec] = std::from_chars(text.data() + from, text.data() + to, v);
        return from < to && ec == std::errc() && p == text.data() + to;
    };
    const bool ok = side(0, x, width) && side(x + 1, text.size(), height);
    return ok && width >= 16 && width <= 8192 && height >= 16 && height <= 8192;
}

CLI::Validator sizeText() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            int w = 0, h = 0;
            return parseSize(text, w, h)
                       ? std::string()
                       : "expected WIDTHxHEIGHT, each 16..8192, got '" + text + "'";
        },
        "WxH");
}

} // namespace specula::cli
