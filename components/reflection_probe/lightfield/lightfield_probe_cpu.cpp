#include "lightfield_probe_cpu.h"

#include "engine/core/glsl_host.h"
#include "engine/image/image_io.h"

#include <cmath>
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

namespace glsl {

// What the GPU reads: each layer's texels as sRGB codes, decoded to linear before the
// bilinear blend (GL_SRGB8_ALPHA8 and the sRGB BC1 format filter in linear space).
struct LightFieldFetches {
    int size = 0; // atlas side
    std::array<std::vector<std::uint8_t>, 6> rgb;
    const std::array<float, 6>* disparity = nullptr;
    float toLinear[256];

    vec3 texel(int slab, int x, int y) const {
        x = x < 0 ? 0 : (x >= size ? size - 1 : x);
        y = y < 0 ? 0 : (y >= size ? size - 1 : y);
        const std::uint8_t* p = &rgb[std::size_t(slab)][(std::size_t(y) * size + x) * 3];
        return vec3(toLinear[p[0]], toLinear[p[1]], toLinear[p[2]]);
    }
    vec3 fetchAtlas(int slab, vec2 t) const {
        const float fx = t.x - 0.5f, fy = t.y - 0.5f;
        const float x0 = std::floor(fx), y0 = std::floor(fy);
        const float ax = fx - x0, ay = fy - y0;
        const int ix = int(x0), iy = int(y0);
        const vec3 top = mix(texel(slab, ix, iy), texel(slab, ix + 1, iy), ax);
        const vec3 bottom = mix(texel(slab, ix, iy + 1), texel(slab, ix + 1, iy + 1), ax);
        return mix(top, bottom, ay);
    }
    float slabDisparity(int slab) const { return (*disparity)[std::size_t(slab)]; }
};

// The shared lookup is included inside a struct so its calls to fetchAtlas and
// slabDisparity bind to the members above.
struct LightFieldTwin : LightFieldFetches {
#include "components/reflection_probe/lightfield/shaders/lightfield_lookup.glsl.h"
};

} // namespace glsl

struct CpuLightFieldProbe::Twin {
    glsl::LightFieldTwin lookup;
    glsl::LightFieldTwin::LightFieldParams params;
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
}

CpuLightFieldProbe::~CpuLightFieldProbe() = default;

glm::vec3 CpuLightFieldProbe::radiance(glm::vec3 p, glm::vec3 d) const {
    return twin_->lookup.lightFieldRadiance(p, d, twin_->params);
}

LightFieldCoords CpuLightFieldProbe::coords(glm::vec3 p, glm::vec3 d) const {
    const glsl::LightFieldTwin::SlabCoords c = twin_->lookup.slabCoords(p, d, twin_->params);
    return {c.slab, c.camera, c.pixel};
}

} // namespace specula
