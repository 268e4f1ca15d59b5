#pragma once
// The flags a bake is made of, shared by `specula-cook bake` and `specula-cook shards`: the
// options themselves (with their help text and checks), the cooking options they give, and
// flavour's settings they give.
#include "assetcooker/lib/cli/setting_flags.h"
#include "assetcooker/lib/cli/tool_cli.h"
#include "assetcooker/lib/level/level_bake.h"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace specula::cook {

// What the bake's flags set. The flavour's own flags are derived from its settings
// declaration (setting_flags.h); --flavour defaults to the first flavour registered.
struct BakeArgs {
    std::string scene, out, flavour;
    std::vector<std::string> probes; // --probe, repeatable
    std::optional<std::string> probeList, sky;
    // a sharded light-field bake (shards, bake --slurm): camera rows a part shard traces
    std::optional<int> shardRows;
    SettingFlags flags;
};

// Adds SCENE, --out and every flavour's flags to `sub`, and maps the library's field names
// onto the flags.
void addBakeOptions(cli::ToolCli& tool, CLI::App* sub, BakeArgs& a);

// The cooking options the flags give (the flavour's settings by --flavour), after the checks
// that need no scene: a flag of another flavour, the light field's atlas size, the PEM
// settings. Throws UsageError naming the flag.
CookOptions checkedCookOptions(const BakeArgs& a);

// The --shard-rows of a sharded bake: 0 when not given (NUM: one part a slab), else checked
// against the light field's --cameras in `options` (checkedCookOptions: 1 .. NUM) and the
// flavour (light field only). Throws UsageError naming --shard-rows.
int checkedShardRows(const BakeArgs& a, const CookOptions& options);
// Adds --shard-rows to `sub` (its help names the part shards).
CLI::Option* addShardRowsOption(CLI::App* sub, std::optional<int>& rows);

// A level: the scene has several probes, or the command line gives several (--probe twice,
// --probes FILE).
bool isLevel(const BakeArgs& a, const ProbeScene& scene);

// The level's options: `options` (from checkedCookOptions) with the probe sources. Throws
// UsageError for the PEM flavour (a PEM follows one probe's camera path).
LevelCookOptions levelCookOptions(const BakeArgs& a, const CookOptions& options,
                                  const ProbeScene& scene);

// What a sharded bake (shards, bake --slurm) splits: a level (levelCookOptions), or one PEM
// (its cooking options as they are). Throws UsageError naming `flag` for one probe of the
// distance or light-field flavours: `specula-cook bake` bakes it whole.
LevelCookOptions shardedCookOptions(const BakeArgs& a, const CookOptions& options,
                                    const ProbeScene& scene, const char* flag);

} // namespace specula::cook
