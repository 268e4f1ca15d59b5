#include "animation.h"

#include <algorithm>
#include <cstddef>

#include <glm/gtc/matrix_transform.hpp>

namespace specula {

namespace {

glm::vec3 lerpKeys(const glm::vec3& a, const glm::vec3& b, float s) {
    return a + s * (b - a);
}
glm::quat lerpKeys(const glm::quat& a, const glm::quat& b, float s) {
    return glm::normalize(glm::slerp(a, b, s)); // slerp takes the shorter arc
}
template <typename T> T normalisedKey(const T& v) {
    return v;
}
template <> glm::quat normalisedKey(const glm::quat& v) {
    return glm::normalize(v);
}

} // namespace

template <typename T> T KeyframeTrack<T>::sample(float seconds) const {
    const bool cubic = interpolation == Interpolation::CubicSpline;
    auto value = [&](std::size_t k) { return values[cubic ? 3 * k + 1 : k]; };
    if (seconds <= times.front()) return normalisedKey(value(0));
    if (seconds >= times.back()) return normalisedKey(value(times.size() - 1));
    // The key at or before `seconds` (upper_bound: the first key after it, never the first).
    const std::size_t k =
        std::size_t(std::upper_bound(times.begin(), times.end(), seconds) - times.begin()) - 1;
    const float span = times[k + 1] - times[k];
    const float s = (seconds - times[k]) / span;
    switch (interpolation) {
    case Interpolation::Step:
        return normalisedKey(value(k));
    case Interpolation::Linear:
        return lerpKeys(value(k), value(k + 1), s);
    case Interpolation::CubicSpline: {
        // Hermite basis (glTF 2.0, Appendix C): tangents scaled by the key span.
        const float s2 = s * s, s3 = s2 * s;
        const T outTangent = values[3 * k + 2], inTangent = values[3 * (k + 1)];
        const T v = (2.f * s3 - 3.f * s2 + 1.f) * value(k) +
                    span * (s3 - 2.f * s2 + s) * outTangent +
                    (-2.f * s3 + 3.f * s2) * value(k + 1) + span * (s3 - s2) * inTangent;
        return normalisedKey(v);
    }
    }
    return value(k);
}

template struct KeyframeTrack<glm::vec3>;
template struct KeyframeTrack<glm::quat>;

std::optional<std::pair<float, float>> NodeAnimation::range() const {
    std::optional<std::pair<float, float>> r;
    auto add = [&](const std::vector<float>& times) {
        if (times.empty()) return;
        if (!r) r.emplace(times.front(), times.back());
        r->first = std::min(r->first, times.front());
        r->second = std::max(r->second, times.back());
    };
    add(translation.times);
    add(rotation.times);
    add(scale.times);
    return r;
}

Transform NodeAnimation::at(const Transform& rest, float seconds) const {
    Transform t = rest;
    if (!translation.empty()) t.translation = translation.sample(seconds);
    if (!rotation.empty()) t.rotation = rotation.sample(seconds);
    if (!scale.empty()) t.scale = scale.sample(seconds);
    return t;
}

glm::mat4 animatedWorld(const ecs::Registry& registry, ecs::Entity e, float seconds) {
    glm::mat4 world(1.f);
    for (ecs::Entity n = e; !n.isNull();) {
        const Transform* t = registry.find<Transform>(n);
        if (!t) break;
        const NodeAnimation* a = registry.find<NodeAnimation>(n);
        world = (a ? a->at(*t, seconds) : *t).local() * world;
        n = t->parent;
    }
    return world;
}

std::optional<std::pair<float, float>> animatedRange(const ecs::Registry& registry, ecs::Entity e) {
    std::optional<std::pair<float, float>> r;
    for (ecs::Entity n = e; !n.isNull();) {
        const Transform* t = registry.find<Transform>(n);
        if (!t) break;
        if (const NodeAnimation* a = registry.find<NodeAnimation>(n))
            if (const auto ar = a->range()) {
                if (!r) r = ar;
                r->first = std::min(r->first, ar->first);
                r->second = std::max(r->second, ar->second);
            }
        n = t->parent;
    }
    return r;
}

} // namespace specula
