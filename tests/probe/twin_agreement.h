#pragma once
// Holds a probe shader to its CPU twin pixel by pixel. agreeByPixel: any flavour, on
// frames already rendered. compareWithTwin (distance): the shader renders
// colour and the twin's inputs (probe-local position, reflected direction, read back as
// float32), the twin runs on exactly those inputs with the configuration the system holds
// now, and the two are compared on the mirror pixels of `mask`.
#include "components/reflection_probe/distance/distance_probe_cpu.h"
#include "components/reflection_probe/distance/system/distance_store.h"
#include "engine/image/ggx_albedo.h"
#include "support/probe_room.h"

#include <algorithm>

namespace specula::test {

struct TwinAgreement {
    Image colour;     // what the shader drew
    long layerPx = 0; // mirror pixels a layer answered
    long close = 0;   // of those, within 2e-3 of the twin
    double sum = 0.0; // summed error over layer pixels
    double worst = 0.0;
    long skyPx = 0; // mirror pixels the sky answered
    double worstSky = 0.0;

    double share() const { return layerPx ? double(close) / double(layerPx) : 0.0; }
    double mean() const { return layerPx ? sum / double(layerPx) : 0.0; }
};

// Any flavour's shader colour against radiance(x, l) of its twin, run on the shader's own
// inputs (OUTPUT 1 and 2 frames), over the pixels of `mask`.
struct PixelAgreement {
    long n = 0;     // mask pixels
    long close = 0; // of those, within the tolerance
    double sum = 0.0, worst = 0.0;
    double colourSum = 0.0; // of the shader's mean RGB: that the frame is not black

    double share() const { return n ? double(close) / double(n) : 0.0; }
    double mean() const { return n ? sum / double(n) : 0.0; }
};

template <typename Radiance>
PixelAgreement agreeByPixel(const Image& colour, const Image& pos, const Image& dir,
                            const Image& mask, Radiance radiance, double tolerance) {
    PixelAgreement a;
    for (int y = 0; y < mask.height; ++y)
        for (int x = 0; x < mask.width; ++x) {
            if (mask.at(x, y)[0] < 0.5f) continue;
            const glm::vec3 shader(colour.rgba(x, y));
            const glm::vec3 cpu = radiance(glm::vec3(pos.rgba(x, y)), glm::vec3(dir.rgba(x, y)));
            const double err = glm::length(cpu - shader);
            ++a.n;
            a.sum += err;
            a.worst = std::max(a.worst, err);
            a.colourSum += double(shader.r + shader.g + shader.b) / 3.0;
            if (err < tolerance) ++a.close;
        }
    return a;
}

// The glossy shader's colour over the GGX albedo E(|n.v|, roughness) it multiplied in (|n.v|
// from the OUTPUT 3 frame `nv`, E from the C++ table) on the pixels of `mask`: the prefiltered
// lighting a glossy twin returns. A shader that applied another E, or none, stays off by it.
inline Image withoutGgxAlbedo(const Image& colour, const Image& nv, const Image& mask,
                              float roughness) {
    Image out = colour;
    for (int y = 0; y < mask.height; ++y)
        for (int x = 0; x < mask.width; ++x)
            if (mask.at(x, y)[0] >= 0.5f)
                for (int c = 0; c < 3; ++c)
                    out.at(x, y)[c] = colour.at(x, y)[c] / ggxAlbedo(nv.at(x, y)[0], roughness);
    return out;
}

inline TwinAgreement compareWithTwin(RoomRenderer& renderer, const ProbeRoom& scene,
                                     const CameraView& cam, const Image& mask) {
    TwinAgreement a;
    a.colour = renderer.render(cam, 0);
    const Image pos = renderer.render(cam, 1);
    const Image dir = renderer.render(cam, 2);
    const ecs::Entity probe = scene.probeEntity();
    const DistanceStore& store = *renderer.probes().store<DistanceStore>();
    const CpuDistanceProbe twin(*store.asset(probe), *store.config(probe));
    for (int y = 0; y < mask.height; ++y)
        for (int x = 0; x < mask.width; ++x) {
            if (mask.at(x, y)[0] < 0.5f) continue;
            int fetches = 0;
            bool sky = false;
            const glm::vec3 cpu =
                twin.radiance(glm::vec3(pos.rgba(x, y)), glm::vec3(dir.rgba(x, y)), fetches, &sky);
            const float err = glm::length(cpu - glm::vec3(a.colour.rgba(x, y)));
            if (sky) {
                ++a.skyPx;
                a.worstSky = std::max(a.worstSky, double(err));
                continue;
            }
            ++a.layerPx;
            a.sum += err;
            a.worst = std::max(a.worst, double(err));
            if (err < 2e-3f) ++a.close;
        }
    return a;
}

} // namespace specula::test
