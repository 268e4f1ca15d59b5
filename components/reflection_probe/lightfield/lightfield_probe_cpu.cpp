#include "lightfield_probe_cpu.h"

#include "components/reflection_probe/lightfield/lightfield_mips.h"
#include "engine/core/glsl_host.h"
#include "engine/image/ggx_albedo.h"
#include "engine/image/srgb.h"

#include <cmath>
#include <mutex>
#include <vector>

namespace specula {

std::array<float, 6> effectiveDisparities(const LightFieldAsset& asset, float override_) {
    std::array<float, 6> d{};
    for (int k = 0; k < 6; ++k)
        d[std::size_t(k)] = std::isfinite(override_) && override_ >= 0.f
                                ? override_
                                : asset.slabs[std::size_t(k)].disparity;
    return d;
}

namespace {
thread_local std::uint64_t tFetches = 0; // CpuLightFieldProbe::fetchCount
} // namespace

namespace glsl {

// What the GPU reads: each layer's texels as sRGB codes, decoded to linear before the
// bilinear blend (GL_SRGB8_ALPHA8 and the sRGB BC1 format filter in linear space).
// Mip level k (k >= 1) is read the same way from levels[k - 1] (lightfield_mips.h), decoded.
struct LightFieldFetches {
    using Layers = std::array<std::vector<std::uint8_t>, 6>;
    int size = 0; // atlas side
    Layers rgb;
    std::vector<Layers> levels; // mips 1.., RGB8 sRGB codes
    const std::array<float, 6>* disparity = nullptr;
    float toLinear[256];

    vec3 texel(const std::vector<std::uint8_t>& layer, int n, int x, int y) const {
        x = x < 0 ? 0 : (x >= n ? n - 1 : x);
        y = y < 0 ? 0 : (y >= n ? n - 1 : y);
        const std::uint8_t* p = &layer[(std::size_t(y) * std::size_t(n) + std::size_t(x)) * 3];
        return vec3(toLinear[p[0]], toLinear[p[1]], toLinear[p[2]]);
    }
    vec3 bilinear(const std::vector<std::uint8_t>& layer, int n, vec2 t) const {
        const float fx = t.x - 0.5f, fy = t.y - 0.5f;
        const float x0 = std::floor(fx), y0 = std::floor(fy);
        const float ax = fx - x0, ay = fy - y0;
        const int ix = int(x0), iy = int(y0);
        const vec3 top = mix(texel(layer, n, ix, iy), texel(layer, n, ix + 1, iy), ax);
        const vec3 bottom = mix(texel(layer, n, ix, iy + 1), texel(layer, n, ix + 1, iy + 1), ax);
        return mix(top, bottom, ay);
    }
    vec3 fetchAtlas(int slab, vec2 t) const {
        ++tFetches;
        return bilinear(rgb[std::size_t(slab)], size, t);
    }
    // t in level-0 texel units: the level's own coordinates are t / 2^level (exact in float).
    vec3 fetchAtlasLevel(int slab, vec2 t, int level) const {
        if (level == 0) return fetchAtlas(slab, t);
        ++tFetches;
        return bilinear(levels[std::size_t(level - 1)][std::size_t(slab)], size >> level,
                        t / float(1 << level));
    }
    float slabDisparity(int slab) const { return (*disparity)[std::size_t(slab)]; }
};

// The shared lookups are included inside a struct so their calls to fetchAtlas,
// fetchAtlasLevel and slabDisparity bind to the members above.
struct LightFieldTwin : LightFieldFetches {
#include "components/reflection_probe/lightfield/shaders/lightfield_lookup.glsl.h"
// (after the lookup, whose types it uses)
#include "components/reflection_probe/lightfield/shaders/lightfield_glossy.glsl.h"
};

} // namespace glsl

struct CpuLightFieldProbe::Twin {
    glsl::LightFieldTwin lookup;
    glsl::LightFieldTwin::LightFieldParams params;
    LightFieldCompression compression = LightFieldCompression::None;
    std::once_flag mipsMade;

    // The mips, made on the first glossy lookup (mirror-only users never pay for them), from
    // the decoded level 0 held here: the bytes the store uploads, decoded as the GPU does.
    void makeMips() {
        std::call_once(mipsMade, [this] {
            LightFieldMips mips =
                buildLightFieldMips(lookup.rgb, params.cameras, params.res, compression);
            const int n = lookup.size;
            for (int k = 1; k <= mips.maxLevel(); ++k) {
                auto& level = mips.levels[std::size_t(k - 1)];
                if (compression == LightFieldCompression::BC1)
                    for (auto& layer : level)
                        layer = decodeBC1(layer.data(), n >> k, n >> k);
                lookup.levels.push_back(std::move(level));
            }
        });
    }
};

CpuLightFieldProbe::CpuLightFieldProbe(const LightFieldAsset& a, float disparity)
    : twin_(std::make_unique<Twin>()), disparity_(effectiveDisparities(a, disparity)) {
    glsl::LightFieldTwin& t = twin_->lookup;
    t.size = a.atlasSize();
    t.disparity = &disparity_;
    for (int i = 0; i < 256; ++i)
        t.toLinear[i] = srgbToLinearValue(float(i) / 255.f);
    for (int k = 0; k < 6; ++k) {
        const auto& data = a.slabs[std::size_t(k)].data;
        t.rgb[std::size_t(k)] = a.compression == LightFieldCompression::BC1
                                    ? decodeBC1(data.data(), t.size, t.size)
                                    : data;
    }
    twin_->params.halfCell = a.halfCell();
    twin_->params.cameras = a.cameras;
    twin_->params.res = a.res;
    twin_->compression = a.compression;
}

CpuLightFieldProbe::~CpuLightFieldProbe() = default;

glm::vec3 CpuLightFieldProbe::radiance(glm::vec3 p, glm::vec3 d) const {
    return twin_->lookup.lightFieldRadiance(p, d, twin_->params);
}

namespace {
glsl::LightFieldTwin::LightFieldGlossy
glossySettings(float roughness, const LightFieldGlossyOptions& o, int mipLevels) {
    glsl::LightFieldTwin::LightFieldGlossy g;
    g.roughness = roughness;
    g.rays = o.rays;
    g.raysPerTexel = o.footprint ? o.raysPerTexel : 0.f;
    g.levelBias = o.levelBias;
    g.maxLevel = o.mips ? mipLevels : 0;
    return g;
}
} // namespace

glm::vec3 CpuLightFieldProbe::glossyRadiance(glm::vec3 p, glm::vec3 lhat, glm::vec3 n,
                                             float roughness,
                                             const LightFieldGlossyOptions& o) const {
    if (!(roughness > 0.f)) return radiance(p, lhat);
    twin_->makeMips();
    return twin_->lookup.lightFieldGlossyRadiance(
        p, lhat, n, glossySettings(roughness, o, int(twin_->lookup.levels.size())), twin_->params);
}

int CpuLightFieldProbe::glossyRays(glm::vec3 p, glm::vec3 lhat, glm::vec3 n, float roughness,
                                   const LightFieldGlossyOptions& o) const {
    if (!(roughness > 0.f)) return 0;
    const float nv = twin_->lookup.lightFieldAlbedoCosine(n, lhat);
    return twin_->lookup.lightFieldLobeRays(p, lhat, nv, glossySettings(roughness, o, 0),
                                            twin_->params);
}

glm::vec3 CpuLightFieldProbe::reflectedRadiance(glm::vec3 p, glm::vec3 lhat, glm::vec3 n,
                                                float roughness,
                                                const LightFieldGlossyOptions& o) const {
    if (!(roughness > 0.f)) return radiance(p, lhat);
    const float nv = twin_->lookup.lightFieldAlbedoCosine(n, lhat);
    return glossyRadiance(p, lhat, n, roughness, o) * ggxAlbedo(nv, std::min(roughness, 1.f));
}

std::uint64_t CpuLightFieldProbe::fetchCount() {
    return tFetches;
}

int CpuLightFieldProbe::maxLevel() const {
    return lightFieldMaxLevel(twin_->params.res, twin_->compression);
}

LightFieldCoords CpuLightFieldProbe::coords(glm::vec3 p, glm::vec3 d) const {
    const glsl::LightFieldTwin::SlabCoords c = twin_->lookup.slabCoords(p, d, twin_->params);
    return {c.slab, c.camera, c.pixel};
}

} // namespace specula
