#include "distance_level_cpu.h"

#include "components/reflection_probe/distance/distance_glossy_chain.h"

#include "engine/core/error.h"
#include "engine/core/glsl_host.h"

#include <algorithm>
#include <filesystem>
#include <numeric>

namespace specula {
namespace glsl {
#include "components/reflection_probe/distance/shaders/distance_level_params.glsl.h"
#include "components/reflection_probe/distance/shaders/distance_lookup_types.glsl.h"

// The hooks of distance_level_blend.glsl.h over a level's probes and their twins; the shared
// blend is included inside so its calls bind to them (as the shader's bind to
// distance_level_gpu.glsl).
struct LevelTwinHooks {
    const std::vector<ProbeVolume>& volumes;
    const std::vector<int>& order; // blend order
    const std::vector<std::unique_ptr<CpuDistanceProbe>>& twins;
    // The probes' chains are there: every lookup is the glossy one at `roughness`.
    bool glossy = false;
    float roughness = 0.f;

    int levelCandidateCount() const { return int(order.size()); }
    int levelCandidate(int i) const { return order[std::size_t(i)]; }
    float levelInfluence(int probe, vec3 p) const {
        return influenceWeight(volumes[std::size_t(probe)], p);
    }
    // Ties go to the probe first in blend order.
    int levelNearest(vec3 p) const {
        int best = -1;
        float bestDistance = 0.f;
        for (const int i : order) {
            const float d = distance(p, volumes[std::size_t(i)].position);
            if (best < 0 || d < bestDistance) {
                best = i;
                bestDistance = d;
            }
        }
        return best;
    }
    const CpuDistanceProbe& twin(int probe) const { return *twins[std::size_t(probe)]; }
    vec3 local(int probe, vec3 p) const { return p - twin(probe).config().params.centre; }
    vec3 levelRadiance(int probe, vec3 p, vec3 lhat, int& fetches) const {
        if (!glossy) return twin(probe).radiance(local(probe, p), lhat, fetches);
        const CpuDistanceProbe::GlossySample g =
            twin(probe).glossySample(local(probe, p), lhat, roughness);
        fetches += g.fetches;
        return g.radiance;
    }
    SeenSample levelSeen(int probe, vec3 p, vec3 lhat) const {
        const CpuDistanceProbe::Seen s =
            glossy ? twin(probe).glossySeen(local(probe, p), lhat, roughness)
                   : twin(probe).seenRadiance(local(probe, p), lhat);
        SeenSample q;
        q.radiance = s.radiance;
        q.visibility = s.visibility;
        q.seen = s.seen;
        q.fetches = s.fetches;
        q.t = s.t;
        return q;
    }
    // The sky every probe shares (the level is baked under one sky): a direction lookup.
    vec3 fetchSky(vec3 dir) const { return twins.front()->sky(dir); }

#include "components/reflection_probe/distance/shaders/distance_level_blend.glsl.h"
};
} // namespace glsl

CpuDistanceLevel::CpuDistanceLevel(const std::string& path, const DistanceProbe& settings,
                                   bool glossy)
    : path_(path), glossy_(glossy) {
    DistanceLevel level;
    level.lookup = settings;
    validateDistanceLevel(level, path);
    const LevelIndex index = readLevelIndex(path);
    if (index.flavour != "distance")
        throw Error(path, "flavour", "expected \"distance\", got \"" + index.flavour + "\"");
    // The shader's uniform block holds kMaxLevelProbes: the twin reads no level it cannot.
    if (index.probes.empty() || index.probes.size() > std::size_t(glsl::kMaxLevelProbes))
        throw Error(path, "probes",
                    "the level has " + std::to_string(index.probes.size()) +
                        " probes; a level holds 1 to " + std::to_string(glsl::kMaxLevelProbes));
    const std::filesystem::path dir = std::filesystem::path(path).parent_path();
    for (const LevelProbeEntry& e : index.probes) {
        volumes_.push_back(e.volume);
        assets_.push_back(std::make_unique<DistanceProbeAsset>(
            readDistanceProbe((dir / e.folder / "manifest.json").string())));
        // The twin refuses what the GPU level refuses.
        checkLevelFaceRes(assets_.back()->faceRes, assets_.front()->faceRes, path,
                          assets_.size() - 1);
        twins_.push_back(std::make_unique<CpuDistanceProbe>(
            *assets_.back(), makeLookupConfig(settings, *assets_.back()),
            glossy ? std::make_shared<const CubeChain>(glossyChainOf(*assets_.back())) : nullptr));
    }
    order_.resize(volumes_.size());
    std::iota(order_.begin(), order_.end(), 0);
    std::stable_sort(order_.begin(), order_.end(), [&](int a, int b) {
        return blendsBefore(volumes_[std::size_t(a)], volumes_[std::size_t(b)]);
    });
}

CpuDistanceLevel::~CpuDistanceLevel() = default;

int CpuDistanceLevel::nearest(glm::vec3 p) const {
    return glsl::LevelTwinHooks{volumes_, order_, twins_, false, 0.f}.levelNearest(p);
}

CpuDistanceProbe::Seen CpuDistanceLevel::seen(int i, glm::vec3 p, glm::vec3 lhat) const {
    const glsl::LevelTwinHooks hooks{volumes_, order_, twins_, false, 0.f};
    return hooks.twin(i).seenRadiance(hooks.local(i, p), lhat);
}

LevelSample CpuDistanceLevel::radiance(glm::vec3 p, glm::vec3 lhat, LevelBlend blend, int k,
                                       float roughness) const {
    if (roughness > 0.f && !glossy_)
        throw Error(path_, "glossy chain",
                    "a rough lookup needs the level made with its probes' chains (glossy)");
    LevelSample out;
    if (volumes_.empty()) return out;
    // The shared blend's functions are the struct's (non-const) members, as in every twin.
    glsl::LevelTwinHooks hooks{volumes_, order_, twins_, glossy_, roughness};
    const glsl::LevelTwinHooks::LevelBlendSample s =
        hooks.blendLevel(p, lhat, int(blend), std::clamp(k, 1, glsl::kMaxLevelK));
    out.radiance = s.radiance;
    for (int i = 0; i < s.count; ++i)
        if (s.weight[i] > 0.f) out.weights.emplace_back(s.probe[i], s.weight[i]);
    out.sky = s.sky;
    out.fetches = s.fetches;
    out.hidden = s.hidden;
    out.fallback = s.fallback;
    out.outside = s.outside;
    out.confidence = s.confidence;
    return out;
}

} // namespace specula
