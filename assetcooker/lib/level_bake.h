#pragma once
// Baking a level: every probe of a scene into its own folder beside a level index
// (level_index.h). The probes come from the markup (every "specula_probe" node), from
// `--probe x,y,z` (repeatable) and from a probe list file; a re-bake re-bakes only the probes
// whose inputs changed and says which and why; an interrupted bake leaves every probe baked
// before it intact (each probe folder is replaced atomically, the index after each probe).
#include "assetcooker/lib/cook.h"
#include "components/reflection_probe/level_index.h"
#include "engine/raytrace/embree_scene.h"

#include <ostream>
#include <string>
#include <vector>

namespace specula {

// Where a level's probes come from besides the markup.
struct LevelProbeSources {
    // `--probe x,y,z`, in order: the i-th replaces the position of the markup's i-th probe
    // (keeping its other members), or is a new probe "probe_<i>" when the markup has fewer.
    std::vector<glm::vec3> positions;
    // `--probes FILE.json`: {"probes": [{"name": .., "position": [..], <markup members>}]}
    // (or the bare array). An entry named like a probe already gathered overrides the members
    // it states; others are new probes and need a position. Empty: none.
    std::string file;
};

struct GatheredProbes {
    std::vector<ProbeVolume> probes;
    std::vector<std::string> warnings;
};

// Every probe of the scene with its volumes, validated. Members nobody states take defaults:
// the proxy is the room the probe stands in, measured with rays (each side as far as the
// axis ray from the probe reaches, the environment's bounds where it escapes, or farther to
// the wall that a grid of rays sees behind furniture in the ray's way: a measured room, not
// a guess), the influence is the proxy cut half-way to every other probe inside it (on the
// axis separating them most, reaching one blend distance past the half-way point: a row of
// probes along one hall shares it out), the blend distance 0.5 m, the priority 0, the cell
// 1.5 m. A scene with no probe anywhere gets one at markupProbeCentre named "probe". Throws
// Error naming the file and field on bad input; warns (names both nodes) when two probes
// have equal priority and identical volumes, and (names the node) when a probe lies inside
// solid geometry.
GatheredProbes gatherLevelProbes(ProbeScene& scene, const LevelProbeSources& sources);

// The checksums a probe is baked from: the meshes within its reach (the environment meshes
// the probe sees along 6 x 32 x 32 directions, those overlapping its proxy, and every
// reflector), each in world space with its material; `options` (the flavour's settings,
// as text) with the volume; the sky file's bytes. `environment`: the scene's Embree BVH
// without the reflectors, built once for all probes of a level.
LevelProbeInputs levelProbeInputs(ProbeScene& scene, const EmbreeScene& environment,
                                  const ProbeVolume& probe, const std::string& options);

struct LevelCookOptions {
    CookOptions cook;        // scene, sky, out (the level folder), flavour, progress
    std::string optionsText; // the flavour's settings as text, for the options checksum
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

// Bakes the stale probes of the level into options.cook.out (see above); a line per probe
// on `log`. The folder must be missing, empty or a level folder (it holds level.json).
// Throws Error naming the file and field, Cancelled when cancelled.
LevelCookResult cookLevel(const LevelCookOptions& options, std::ostream* log);
LevelCookResult cookLevel(ProbeScene& scene, const LevelCookOptions& options, std::ostream* log);

} // namespace specula
