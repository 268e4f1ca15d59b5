#include "distance_level_cpu.h"

#include "engine/core/error.h"

#include <algorithm>
#include <filesystem>
#include <numeric>

namespace specula {

const char* toString(LevelBlend b) {
    switch (b) {
    case LevelBlend::Nearest:
        return "nearest";
    case LevelBlend::Engine:
        return "engine";
    case LevelBlend::Visibility:
        return "visibility";
    }
    return "?";
}

CpuDistanceLevel::CpuDistanceLevel(const std::string& path, const DistanceProbe& settings) {
    if (settings.method == DistanceMethod::Layered || settings.method == DistanceMethod::Planned ||
        settings.method == DistanceMethod::AvgDist)
        throw Error(path, "method",
                    std::string("a level blends single-layer lookups: ") +
                        toString(settings.method) +
                        " is not one (envmap, boxproj, bisection, "
                        "secant)");
    const LevelIndex index = readLevelIndex(path);
    if (index.flavour != "distance")
        throw Error(path, "flavour", "expected \"distance\", got \"" + index.flavour + "\"");
    const std::filesystem::path dir = std::filesystem::path(path).parent_path();
    for (const LevelProbeEntry& e : index.probes) {
        volumes_.push_back(e.volume);
        assets_.push_back(std::make_unique<DistanceProbeAsset>(
            readDistanceProbe((dir / e.folder / "manifest.json").string())));
        DistanceProbe s = settings;
        twins_.push_back(std::make_unique<CpuDistanceProbe>(*assets_.back(),
                                                            makeLookupConfig(s, *assets_.back())));
    }
}

CpuDistanceLevel::~CpuDistanceLevel() = default;

int CpuDistanceLevel::nearest(glm::vec3 p) const {
    int best = -1;
    for (int i = 0; i < int(volumes_.size()); ++i) {
        if (best < 0) {
            best = i;
            continue;
        }
        const float di = glm::distance(p, volumes_[std::size_t(i)].position);
        const float db = glm::distance(p, volumes_[std::size_t(best)].position);
        if (di < db ||
            (di == db && volumes_[std::size_t(i)].name < volumes_[std::size_t(best)].name))
            best = i;
    }
    return best;
}

CpuDistanceProbe::Seen CpuDistanceLevel::seen(int i, glm::vec3 p, glm::vec3 lhat) const {
    return twins_.at(std::size_t(i))->seenRadiance(p - volumes_.at(std::size_t(i)).position, lhat);
}

LevelSample CpuDistanceLevel::radiance(glm::vec3 p, glm::vec3 lhat, LevelBlend blend, int k) const {
    LevelSample out;
    if (volumes_.empty()) return out;
    const auto local = [&](int i) { return p - volumes_[std::size_t(i)].position; };
    const auto plain = [&](int i) {
        int fetches = 0;
        const glm::vec3 c = twins_[std::size_t(i)]->radiance(local(i), lhat, fetches);
        out.fetches += fetches;
        return c;
    };
    // The sky every probe shares (the level is baked under one sky): a direction lookup.
    const auto sky = [&] {
        ++out.fetches;
        return twins_.front()->sky(lhat);
    };
    const ProbeBlend engine = blendProbes(volumes_, p, k);
    if (blend == LevelBlend::Nearest || engine.weights.empty()) {
        // Outside every influence volume: the nearest probe alone.
        const int i = nearest(p);
        out.weights = {{i, 1.f}};
        out.radiance = plain(i);
        out.fallback = blend != LevelBlend::Nearest;
        out.outside = engine.weights.empty();
        return out;
    }
    if (blend == LevelBlend::Engine) {
        for (const auto& [i, w] : engine.weights) {
            out.radiance += w * plain(int(i));
            out.weights.emplace_back(int(i), w);
        }
        out.sky = engine.sky;
        if (out.sky > 0.f) out.radiance += out.sky * sky();
        return out;
    }
    // Visibility: the engine's order and influences, each probe weighed by how surely it
    // sees what it proposes (shaders/distance_seen.glsl.h); every probe with influence here,
    // not only those the engine's weights reached before summing to 1, so a hidden first
    // probe leaves its share to the next ones.
    float remaining = 1.f, confidence = 0.f;
    for (const std::size_t i : influencingProbes(volumes_, p, k)) {
        const ProbeVolume& v = volumes_[i];
        const CpuDistanceProbe::Seen s = seen(int(i), p, lhat);
        out.fetches += s.fetches;
        if (!s.seen) ++out.hidden;
        confidence = std::min(1.f, confidence + influenceWeight(v, p) * s.visibility);
        const float weight = influenceWeight(v, p) * s.visibility * remaining;
        if (weight <= 0.f) continue;
        out.radiance += weight * s.radiance;
        out.weights.emplace_back(int(i), weight);
        remaining -= weight;
    }
    if (out.weights.empty()) {
        // No probe with influence here sees the hit: the engine's blend, flagged.
        LevelSample e = radiance(p, lhat, LevelBlend::Engine, k);
        e.hidden = out.hidden;
        e.fallback = true;
        e.fetches += out.fetches;
        return e;
    }
    // What the probes that see it leave goes to them in proportion (not to the sky: the
    // hidden probes' share is a wall's, not the sky's), then the engine's own sky share.
    const float taken = 1.f - remaining;
    const float skyShare = engine.sky;
    const float scale = (1.f - skyShare) / taken;
    out.radiance *= scale;
    for (auto& [i, w] : out.weights)
        w *= scale;
    out.sky = skyShare;
    if (skyShare > 0.f) out.radiance += skyShare * sky();
    out.confidence = confidence;
    if (confidence >= 1.f) return out;
    // Confidence: the seen probes' influence, the sum of influence x visibility (at most 1).
    // Below 1 the result fades towards the engine's blend, so a probe entering over its blend
    // distance, or a verdict near its edge, changes the pixel gradually, never in one frame.
    const LevelSample e = radiance(p, lhat, LevelBlend::Engine, k);
    out.radiance = confidence * out.radiance + (1.f - confidence) * e.radiance;
    for (auto& [i, w] : out.weights)
        w *= confidence;
    for (const auto& [i, w] : e.weights) {
        auto same = std::find_if(out.weights.begin(), out.weights.end(),
                                 [&](const auto& q) { return q.first == i; });
        if (same != out.weights.end())
            same->second += (1.f - confidence) * w;
        else
            out.weights.emplace_back(i, (1.f - confidence) * w);
    }
    out.fetches += e.fetches;
    return out;
}

} // namespace specula
