#include "pem_probe_cpu.h"

#include "components/reflection_probe/walk_path.h"

namespace specula {

std::vector<float> pemSampleParameters(const PemAsset& asset) {
    std::vector<float> out;
    out.reserve(asset.samples.size());
    for (const PemSampleMap& s : asset.samples)
        out.push_back(s.parameter);
    return out;
}

glsl::PemParams pemParams(const PemAsset& asset, const PemProbe& settings) {
    // Every walk path is a closed loop (walk_path.h): past the last sample the blend runs on
    // to the first. A path this build does not know is treated as open.
    WalkPath path;
    const bool closed = parseWalkPath(asset.path, path);
    const PemBlendWeights w =
        pemBlend(pemSampleParameters(asset), settings.parameter, settings.nearest, closed);
    glsl::PemParams p{};
    p.boxMin = asset.boxMin;
    p.boxMax = asset.boxMax;
    p.faceRes = asset.faceRes;
    p.centre = asset.centre;
    p.wb = w.wb;
    p.layerA = 6 * w.a;
    p.layerB = 6 * w.b;
    p.mapLevels = asset.mipLevels;
    if (const PemDistanceGeometry* g = asset.distance.get()) {
        p.distanceFaceRes = g->faceRes;
        p.dInf = g->dInf;
        p.range = g->range;
        p.tolerance = g->tolerance;
        p.maxSteps = g->maxSteps;
    }
    if (asset.localLayer) {
        p.localFaceRes = asset.localFaceRes;
        p.localCentre = asset.localSphere.centre;
        p.localRadius = asset.localSphere.radius;
    }
    return p;
}

glm::vec3 PemProbeCpu::radiance(glm::vec3 x, glm::vec3 l, bool onHull,
                                const PemFootprint& f) const {
    // As the shader: sample a's lookup, mixed with sample b's when b has any weight.
    auto sample = [&](int layer) {
        return PemLookupCpu(asset_->samples[std::size_t(layer / 6)].map).radiance(x, l, f);
    };
    glm::vec3 colour = sample(params_->layerA);
    if (params_->wb > 0.f) colour = glm::mix(colour, sample(params_->layerB), params_->wb);
    if (!asset_->localLayer || onHull) return colour;
    // The shader blends the local texels as it fetches them: linear, so blending lookups is
    // the same up to rounding.
    auto local = [&](int layer) {
        return PemLookupCpu(asset_->samples[std::size_t(layer / 6)].local).localRadiance(x, l);
    };
    glm::vec4 over = local(params_->layerA);
    if (params_->wb > 0.f) over = glm::mix(over, local(params_->layerB), params_->wb);
    return glm::vec3(over) + (1.f - over.a) * colour;
}

} // namespace specula
