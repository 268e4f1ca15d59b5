#pragma once
// Keyframed node transforms (glTF animations): a node's translation, rotation and scale as
// functions of time. A plain component beside Transform, which keeps the rest pose; whoever
// plays an animation asks for the transform at a time and leaves the registry as it was.
#include "engine/ecs/registry.h"
#include "engine/scene/components.h"

#include <optional>
#include <utility>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace specula {

// glTF's sampler interpolations: Linear (slerp for rotations), Step (the previous key's value)
// and CubicSpline (Hermite through the keys with the file's tangents; rotations normalised).
enum class Interpolation { Linear, Step, CubicSpline };

template <typename T> struct KeyframeTrack {
    Interpolation interpolation = Interpolation::Linear;
    std::vector<float> times; // seconds, finite, strictly increasing
    // One value per time; CubicSpline: three per time, in-tangent, value, out-tangent.
    std::vector<T> values;

    bool empty() const { return times.empty(); }
    // The value at `seconds` (the track not empty), held at the first and last keys outside
    // their range.
    T sample(float seconds) const;
};

struct NodeAnimation {
    KeyframeTrack<glm::vec3> translation, scale;
    KeyframeTrack<glm::quat> rotation;

    // The first and last key over the tracks the node has; nullopt when it has none.
    std::optional<std::pair<float, float>> range() const;
    // `rest` with the animated channels replaced by their values at `seconds`.
    Transform at(const Transform& rest, float seconds) const;
};

// The world matrix of `e` at `seconds`: every node from it to the root takes its
// NodeAnimation (when it has one) at that time, the others their rest pose.
glm::mat4 animatedWorld(const ecs::Registry& registry, ecs::Entity e, float seconds);

// The time span over the animations of `e` and its ancestors; nullopt when none moves it.
std::optional<std::pair<float, float>> animatedRange(const ecs::Registry& registry, ecs::Entity e);

} // namespace specula
