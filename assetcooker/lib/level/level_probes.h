#pragma once
// The probes of a level: gathered from the markup, `--probe` and a probe list file, with
// their default volumes (a measured room for the proxy, an influence shared out between
// probes in one room).
#include "assetcooker/lib/scene/probe_setup.h"
#include "components/reflection_probe/probe_volume.h"

#include <glm/vec3.hpp>

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
// Error naming the file and field on bad input: among others an unknown member (a misspelt
// key), a priority outside int, two list entries of one name, a probe outside its own
// proxy box, and more probes than the runtime draws in one view (kMaxLevelProbes); warns (names
// both nodes) when two probes have equal priority and identical volumes, and (names the node) when
// a probe lies inside solid geometry.
GatheredProbes gatherLevelProbes(ProbeScene& scene, const LevelProbeSources& sources);

} // namespace specula
