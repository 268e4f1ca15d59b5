#pragma once
// Where a probe applies, as every engine's probe set has it (Unity, Godot, Unreal, Bevy): the
// proxy box its lookup assumes (box projection, the rectification's range), the influence
// volume it is blended over (a box or a sphere, may differ from the proxy), a blend distance
// over which its weight fades in from the influence's boundary, and a priority. Plain data:
// the cooker reads it from the markup and the command line, records it in a level's index,
// and the runtime blends probes with it.
//
// In a scene's markup, every member optional, boxes relative to the probe's position:
//   "specula_probe": {"proxy": {"min": [x,y,z], "max": [x,y,z]},
//                     "influence": {"box": {"min": [..], "max": [..]}} | {"sphere": {"radius": r}},
//                     "blend_distance": 0.5, "priority": 0, "cell_size": 1.5}
#include "engine/math/aabb.h"

#include <span>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json_fwd.hpp>

namespace specula {

struct ProbeInfluence {
    enum class Shape { Box, Sphere };
    Shape shape = Shape::Box;
    Aabb box;              // world space (Box)
    glm::vec3 centre{0.f}; // world space (Sphere)
    float radius = 0.f;    // (Sphere)

    bool operator==(const ProbeInfluence&) const = default;
};

struct ProbeVolume {
    std::string name;        // the probe's node (or the name a probe list gives it)
    glm::vec3 position{0.f}; // world space: where the probe captured
    Aabb proxy;              // world space
    ProbeInfluence influence;
    float blendDistance = 0.5f; // metres, >= 0
    int priority = 0;           // higher wins
    float cellSize = 1.5f;      // side of the cubic cell reflectors move in

    bool operator==(const ProbeVolume&) const = default;
};

// How far `p` lies inside the influence volume, in metres: the distance to its nearest
// boundary face (box) or to its surface (sphere); negative outside.
// The shape as shaders/probe_influence.glsl.h codes it (kInfluenceBox, kInfluenceSphere).
int influenceShapeCode(const ProbeInfluence& influence);
float influenceDepth(const ProbeInfluence& influence, glm::vec3 p);
// The probe's own weight at `p` before blending: 0 outside the influence, rising linearly
// over the blend distance from the boundary to 1 (1 everywhere inside when the blend
// distance is 0).
float influenceWeight(const ProbeVolume& probe, glm::vec3 p);
// The order engines blend probes in: higher priority first, then the smaller influence
// volume (the more specific probe), then the name (a deterministic tie-break).
bool blendsBefore(const ProbeVolume& a, const ProbeVolume& b);

// Engine-style blending (influence, blend distance, priority): up to `k` probes in blend
// order each take weight_i x (1 - what the ones before took); the rest is the sky's.
struct ProbeBlend {
    std::vector<std::pair<std::size_t, float>> weights; // (index into probes, weight) > 0
    float sky = 1.f;                                    // 1 - sum of the weights
};
ProbeBlend blendProbes(std::span<const ProbeVolume> probes, glm::vec3 p, int k);
// The probes whose influence reaches p, in blend order, at most k: what a blend that may
// drop some of them (by visibility) walks, past where the engine's weights already sum to 1.
std::vector<std::size_t> influencingProbes(std::span<const ProbeVolume> probes, glm::vec3 p, int k);

// [x, y, z] of finite numbers within kMaxCoordinate (manifest_fields.h); throws Error naming
// `file` and `field`.
glm::vec3 probeVec3(const nlohmann::json& a, const std::string& file, const std::string& field);

// The volume's members as JSON (world space, the level index's form) and back.
nlohmann::json toJson(const ProbeVolume& v);
// Reads the level index's form; throws Error naming `file` and `field` + the member.
ProbeVolume probeVolumeFromJson(const nlohmann::json& j, const std::string& file,
                                const std::string& field);

// Applies the markup members of a "specula_probe" object (probe-relative boxes, see above)
// onto `volume`, whose position is already set; members absent leave `volume` as it is.
// Throws Error naming `file` and `field` + the member when one is malformed, zero-size or
// inverted.
void applyProbeMarkup(ProbeVolume& volume, const nlohmann::json& options, const std::string& file,
                      const std::string& field);
// Throws Error naming the member when the volume cannot be blended with (an empty or
// inverted proxy or influence, a negative blend distance, a non-finite number).
void validateProbeVolume(const ProbeVolume& volume, const std::string& file,
                         const std::string& field);

} // namespace specula
