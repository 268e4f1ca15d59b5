#pragma once
// The CPU twin of the light-field shader: the same lookup code
// (shaders/lightfield_lookup.glsl.h) compiled as C++ over the cooked atlas, with bilinear
// fetches that read what the GPU reads (sRGB texels decoded to linear before filtering, BC1
// decoded first, clamped to the layer). Tests hold the shader to it pixel by pixel.
#include "components/reflection_probe/lightfield/lightfield_asset.h"

#include <array>
#include <memory>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace specula {

// Continuous indices of a ray's slab lookup, before clamping (exposed for the coverage tests).
struct LightFieldCoords {
    int slab = 0;
    glm::vec2 camera{0.f};
    glm::vec2 pixel{0.f};
};

class CpuLightFieldProbe {
public:
    // disparity: pixels per camera step for all slabs; < 0 or NaN: the cooked per-slab values.
    explicit CpuLightFieldProbe(const LightFieldAsset& asset, float disparity = -1.f);
    ~CpuLightFieldProbe();

    // p: cell-local reflector point, d: reflected direction (need not be unit).
    glm::vec3 radiance(glm::vec3 p, glm::vec3 d) const;
    LightFieldCoords coords(glm::vec3 p, glm::vec3 d) const;

    // The disparities the lookup uses (cooked or the override).
    const std::array<float, 6>& disparities() const { return disparity_; }

private:
    struct Twin;
    std::unique_ptr<Twin> twin_;
    std::array<float, 6> disparity_{};
};

// Effective per-slab disparity: the override when it is finite and >= 0, else the cooked.
std::array<float, 6> effectiveDisparities(const LightFieldAsset& asset, float override_);

} // namespace specula
