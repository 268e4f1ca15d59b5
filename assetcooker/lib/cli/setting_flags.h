#pragma once
// The bake's flavour flags, derived from every flavour's settings declaration
// (settings/setting.h, visitSettings): one option per flag (a flag several flavours declare,
// such as --face-res, is one option whose help gives each one's), checked when parsed against
// what some flavour accepts, then read into the chosen flavour's settings, which refuses a
// flag it does not declare. `--config` keys are the flags' names, so they follow too.
#include "assetcooker/lib/bake/cook.h"
#include "assetcooker/lib/cli/setting_text.h"
#include "assetcooker/lib/cli/tool_cli.h"

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace specula::cook {

class SettingFlags {
public:
    // Adds every flavour's flags to `sub` and maps each setting's key onto its flag, so an
    // error of library code naming the field ("face_res") names the flag instead. With
    // `flavour` and `only`, that flavour's flags among `only` alone (a command that takes
    // some of one flavour's settings, as `plan` does).
    void add(cli::ToolCli& tool, CLI::App* sub, const std::string& flavour = "",
             const std::vector<std::string>& only = {});
    // The settings of `flavour` (a CookFlavour's kFlavour) from the flags given, checked
    // (checkCookSettings against `file`). Throws UsageError naming the flag: one this
    // flavour does not declare, or a value it refuses.
    CookFlavour settings(const std::string& flavour, const std::string& file) const;
    // Whether `flag` was given on the command line or in --config.
    bool given(const std::string& flag) const;

private:
    struct Flag {
        std::string text; // as given
        CLI::Option* option = nullptr;
        std::vector<std::string> flavours, helps; // those that declare it, and their help
        std::string kind;                         // "INT", "FLOAT", "TEXT"
    };
    std::map<std::string, Flag> flags_; // by flag; a map: the options bind to `text`
};

} // namespace specula::cook
