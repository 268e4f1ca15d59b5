#include "gltf_animation.h"

#include "engine/scene/gltf_accessors.h"

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace specula::gltf_internal {

namespace {

Interpolation interpolation(const Context& ctx, const std::string& name, const std::string& field) {
    if (name == "LINEAR" || name.empty()) return Interpolation::Linear;
    if (name == "STEP") return Interpolation::Step;
    if (name == "CUBICSPLINE") return Interpolation::CubicSpline;
    ctx.fail(field, "expected LINEAR, STEP or CUBICSPLINE, got '" + name + "'");
}

std::vector<float> keyTimes(const Context& ctx, int accessor, const std::string& field) {
    std::vector<float> times = readFloats(ctx, accessor, 1, field);
    if (times.empty()) ctx.fail(field, "an animation sampler needs at least one key");
    for (std::size_t k = 0; k < times.size(); ++k) {
        if (!std::isfinite(times[k]))
            ctx.fail(field, "key " + std::to_string(k) + " time is not finite");
        if (k > 0 && !(times[k] > times[k - 1]))
            ctx.fail(field, "key times must increase strictly; key " + std::to_string(k) +
                                " is at " + std::to_string(times[k]) + " s, after " +
                                std::to_string(times[k - 1]) + " s");
    }
    return times;
}

// The sampler's output as `comps` floats a value, as many values as the keys want.
std::vector<float> keyValues(const Context& ctx, int accessor, int comps, std::size_t values,
                             const std::string& field) {
    std::vector<float> raw = readFloats(ctx, accessor, comps, field);
    if (raw.size() != values * std::size_t(comps))
        ctx.fail(field, "expected " + std::to_string(values) + " values for the keys, got " +
                            std::to_string(raw.size() / std::size_t(comps)));
    for (float v : raw)
        if (!std::isfinite(v)) ctx.fail(field, "a value is not finite");
    return raw;
}

template <typename T>
void setTrack(const Context& ctx, KeyframeTrack<T>& track, Interpolation mode,
              std::vector<float> times, std::vector<T> values, const std::string& field) {
    if (!track.empty()) ctx.fail(field, "a second channel drives the same node and path");
    track.interpolation = mode;
    track.times = std::move(times);
    track.values = std::move(values);
}

} // namespace

std::map<int, NodeAnimation> readNodeAnimations(Context& ctx) {
    std::map<int, NodeAnimation> out;
    const auto& animations = ctx.model().animations;
    if (animations.empty()) return out;
    if (animations.size() > 1)
        ctx.warn("animations", std::to_string(animations.size() - 1) +
                                   " animation(s) after the first skipped; animations[0] is "
                                   "loaded");
    const tinygltf::Animation& a = animations[0];
    for (std::size_t c = 0; c < a.channels.size(); ++c) {
        const tinygltf::AnimationChannel& ch = a.channels[c];
        const std::string cf = "animations[0].channels[" + std::to_string(c) + "]";
        const std::string& path = ch.target_path;
        if (path == "weights") {
            ctx.warn(cf + ".target.path", "morph target weights skipped");
            continue;
        }
        if (path != "translation" && path != "rotation" && path != "scale")
            ctx.fail(cf + ".target.path",
                     "expected translation, rotation, scale or weights, got '" + path + "'");
        ctx.at(ctx.model().nodes, ch.target_node, "nodes", cf + ".target.node");
        const auto& sampler = ctx.at(a.samplers, ch.sampler, "samplers", cf + ".sampler");
        const std::string sf = "animations[0].samplers[" + std::to_string(ch.sampler) + "]";
        const Interpolation mode = interpolation(ctx, sampler.interpolation, sf + ".interpolation");
        std::vector<float> times = keyTimes(ctx, sampler.input, sf + ".input");
        const std::size_t values =
            times.size() * (mode == Interpolation::CubicSpline ? std::size_t(3) : std::size_t(1));
        NodeAnimation& node = out[ch.target_node];
        if (path == "rotation") {
            const std::vector<float> raw =
                keyValues(ctx, sampler.output, 4, values, sf + ".output");
            std::vector<glm::quat> q(values);
            for (std::size_t k = 0; k < values; ++k) {
                // glTF stores x, y, z, w; glm's constructor takes w first.
                q[k] = glm::quat(raw[4 * k + 3], raw[4 * k], raw[4 * k + 1], raw[4 * k + 2]);
                const bool tangent = mode == Interpolation::CubicSpline && k % 3 != 1;
                if (!tangent && !(glm::length(q[k]) > 1e-6f))
                    ctx.fail(sf + ".output",
                             "rotation key " + std::to_string(k) + " is zero: no rotation");
            }
            setTrack(ctx, node.rotation, mode, std::move(times), std::move(q), cf);
            continue;
        }
        const std::vector<float> raw = keyValues(ctx, sampler.output, 3, values, sf + ".output");
        std::vector<glm::vec3> v(values);
        for (std::size_t k = 0; k < values; ++k)
            v[k] = {raw[3 * k], raw[3 * k + 1], raw[3 * k + 2]};
        setTrack(ctx, path == "translation" ? node.translation : node.scale, mode, std::move(times),
                 std::move(v), cf);
    }
    return out;
}

} // namespace specula::gltf_internal
