#pragma once
// Baking a level: every probe of a scene into its own folder beside a level index
// (level_index.h). The probes come from the markup (every "specula_probe" node), from
// `--probe x,y,z` (repeatable) and from a probe list file; a re-bake re-bakes only the probes
// whose inputs changed and says which and why; an interrupted bake leaves every probe baked
// before it intact (each probe folder is replaced atomically, the index after each probe).
#include "assetcooker/lib/bake/cook.h"
#include "assetcooker/lib/level/level_probes.h"
#include "assetcooker/lib/scene/probe_inputs.h"
#include "components/reflection_probe/level_index.h"
#include "engine/raytrace/embree_scene.h"

#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace specula {

// What differs between `scene` and the scene the level `index` (read from `indexPath`) was
// baked from: one line per probe whose geometry within reach or sky checksum differs, naming
// the probe and its index field. Empty when the level fits the scene. The options are not
// compared: a loader holds no bake settings; nor the sky when `compareSky` is false (a
// loader that lights its scene with the level's own copy of the sky).
std::vector<std::string> levelStaleness(ProbeScene& scene, const LevelIndex& index,
                                        const std::string& indexPath, bool compareSky);

struct LevelCookOptions {
    // scene, sky, out (the level folder), flavour (every setting of which is in the probes'
    // options checksum), progress
    CookOptions cook;
    LevelProbeSources sources;
};

struct LevelProbeOutcome {
    std::string name, folder;
    bool baked = false;
    std::string reason; // why it was (re)baked, or "up to date"
    double seconds = 0;
};

struct LevelCookResult {
    std::string index; // DIR/level.json
    std::vector<LevelProbeOutcome> probes;
    std::vector<std::string> warnings;
    double seconds = 0;
};

// A level planned against what its folder holds: every probe's index entry in the scene's
// order (a fresh probe's with its manifest checksum) and why each is stale (empty: up to
// date); the placement warnings (also on `log`). Throws Error naming the file and field.
struct LevelPlan {
    LevelIndex index;
    std::vector<std::string> reasons;
    std::optional<LevelIndex> previous;
    std::vector<std::string> warnings;
};
LevelPlan planLevel(ProbeScene& scene, const LevelCookOptions& options, std::ostream* log);

// The cooking options of one probe of the level, baked into `out`.
CookOptions levelProbeCookOptions(const ProbeScene& scene, const LevelCookOptions& options,
                                  const LevelProbeEntry& entry, const std::string& out);

// A warning (also on `log`) for each probe of the previous index no longer in the level.
void warnOfDroppedProbes(const LevelPlan& plan, const std::string& dir,
                         std::vector<std::string>& warnings, std::ostream* log);

// Bakes the stale probes of the level into options.cook.out (see above); a line per probe
// on `log`. The folder must be missing, empty or a level folder (it holds level.json).
// Throws Error naming the file and field, Cancelled when cancelled.
LevelCookResult cookLevel(const LevelCookOptions& options, std::ostream* log);
LevelCookResult cookLevel(ProbeScene& scene, const LevelCookOptions& options, std::ostream* log);

} // namespace specula
