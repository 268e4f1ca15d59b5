#pragma once
// The command-line front shared by specula-cook and specula-sandbox, on CLI11: subcommands with
// generated --help, validators, `--config FILE` (TOML/INI, one [section] per subcommand; flags
// on the command line win) and one error policy: every failure is one line on stderr, and the
// exit status says what failed.
#include <CLI/CLI.hpp>
#include <glm/vec3.hpp>

#include <functional>
#include <map>
#include <ostream>
#include <set>
#include <span>
#include <string>

namespace specula::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;     // the input could not be processed
inline constexpr int kExitUsage = 2;       // the command line itself is wrong
inline constexpr int kExitCancelled = 130; // 128 + SIGINT: stopped by a signal, nothing replaced

// What a subcommand does once its options are parsed; returns the exit status.
using Action = std::function<int(std::ostream& out)>;

class ToolCli {
public:
    ToolCli(std::string tool, std::string description);

    CLI::App& app() { return app_; }
    // Adds a subcommand: `summary` is its line in the tool's --help; `description` and
    // `footer` frame its own generated --help. `run` is called when it is chosen.
    CLI::App* addSubcommand(const std::string& name, const std::string& summary,
                            const std::string& description, const std::string& footer, Action run);
    // Library code names the field it read (Error("", "face_res", ...)); when such an error
    // reaches the tool, the message names the flag that set the field instead.
    void mapField(const std::string& field, const std::string& flag) { fieldFlags_[field] = flag; }
    // Every value is checked before the subcommand's own validators see it: integers are
    // decimal (010 is ten, never octal; 0x10 is refused), numbers finite (no nan or inf),
    // and no value is empty, except that of an option allowed here (e.g. --sky '': a black
    // sky). `--config FILE` must name a regular file.
    CLI::Option* allowEmpty(CLI::Option* option) {
        emptyAllowed_.insert(option);
        return option;
    }

    // Parses argv[1..] and runs the chosen subcommand. Never throws.
    int run(std::span<const std::string> args, std::ostream& out, std::ostream& err);

private:
    int dispatch(std::span<const std::string> args, std::ostream& out);
    void checkValues(); // adds the value checks above to every option, once
    std::string describe(const std::exception& e) const;

    CLI::App app_;
    std::map<const CLI::App*, Action> actions_;
    std::map<std::string, std::string> fieldFlags_;
    std::set<const CLI::Option*> emptyAllowed_;
    bool valuesChecked_ = false;
};

// Validators shared by the subcommands.
// A finite number in [lo, hi] (CLI::Range lets NaN through).
CLI::Validator finiteRange(double lo, double hi);
// A non-empty value, e.g. a folder name.
CLI::Validator nonEmpty(const std::string& what);
// A decimal integer ('-' only when `isSigned`), leading zeros dropped ("010" becomes "10");
// what ToolCli checks every integer option with.
CLI::Validator decimalInteger(bool isSigned);
// "x,y,z": three finite numbers of magnitude at most 1e7.
CLI::Validator vec3Text();
glm::vec3 parseVec3(const std::string& text);
// "WxH", each side 16..8192; false (width and height unspecified) otherwise.
bool parseSize(const std::string& text, int& width, int& height);
CLI::Validator sizeText();

} // namespace specula::cli
