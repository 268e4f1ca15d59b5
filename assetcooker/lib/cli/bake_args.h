#pragma once
// The flags a bake is made of, shared by `specula-cook bake` and `specula-cook shards`: the
// options themselves (with their help text and checks), the cooking options they give, and
// the flavour's settings as text (a level's options checksum).
#include "assetcooker/lib/cli/tool_cli.h"
#include "assetcooker/lib/level/level_bake.h"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace specula::cook {

// What the bake's flags set; defaults are the help's.
struct BakeArgs {
    std::string scene, out, flavour = "distance";
    std::vector<std::string> probes; // --probe, repeatable
    std::optional<std::string> probeList, sky;
    // distance and pem
    std::optional<int> faceRes; // distance: 256, pem: 128
    // distance
    std::string layers = "plan", glossy = "auto";
    std::string plan = "measured";        // --plan measured|analytic
    std::optional<std::string> maxError;  // --max-error "32dB" | "rmse:0.03"
    std::optional<double> maxMibPerProbe; // --max-mib-per-probe
    // lightfield
    std::optional<float> cellSize;
    std::optional<std::string> cellCentre;
    int cameras = 8, imageRes = 64;
    std::string compress = "none";
    // a sharded light-field bake (shards, bake --slurm): camera rows a part shard traces
    std::optional<int> shardRows;
    // pem
    int samples = 8, supersample = 1, mipLevels = 1;
    std::string imageSize = "640x480", geometry = "distance";
    float prior = 0.05f, smoothness = 0.02f;
    std::string parameter = "viewpoint", path = "orbit";
    std::string localLayer = "auto";
    std::string rows = "subray";
    std::string nonNegative = "on";
    float roundingReach = PemCookSettings{}.roundingReach;
    // The options that belong to some flavours only, with their names ("distance|pem").
    std::vector<std::pair<const CLI::Option*, std::string>> flavourOnly;
};

// Adds SCENE, --out and every flavour's flags to `sub`, and maps the library's field names
// onto the flags.
void addBakeOptions(cli::ToolCli& tool, CLI::App* sub, BakeArgs& a);

// The cooking options the flags give (the flavour's settings by --flavour), after the checks
// that need no scene: a flag of another flavour, the light field's atlas size, the PEM
// settings. Throws UsageError naming the flag.
CookOptions checkedCookOptions(const BakeArgs& a);

// The --shard-rows of a sharded bake: 0 when not given (NUM: one part a slab), else checked
// against --cameras (1 .. NUM) and the flavour (light field only). Throws UsageError naming
// --shard-rows.
int checkedShardRows(const BakeArgs& a);
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
