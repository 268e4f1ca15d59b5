#pragma once
// The fixture of the light-field glossy tests on the room (lightfield_glossy_test.cpp,
// lightfield_glossy_rays_test.cpp): assets/room with a light-field probe of NUM 8, RES 64
// baked once per suite through the cooking library, the CPU twin over it, and the reflector
// pixels of a camera, cell-local. No GL: the twin and Embree.
#include "assetcooker/lib/flavours/lightfield/lightfield_bake.h"
#include "assetcooker/lib/scene/probe_setup.h"
#include "assetcooker/lib/scene/reflector_pixels.h"
#include "components/reflection_probe/lightfield/lightfield_probe_cpu.h"
#include "engine/raytrace/ground_truth.h"
#include "support/probe_room.h"

#include <gtest/gtest.h>

#include <random>

#include <glm/geometric.hpp>
#include <vector>

namespace specula::test {

// A mirror pixel of the camera: where the reflector is read (cell-local), its shading normal
// and mirror direction, found as the reflector pass finds them (safeNormal, mirrorDirection).
struct MirrorPixel {
    int px, py;
    glm::vec3 p, n, lhat;
};

inline std::vector<MirrorPixel> mirrorPixels(const GroundTruthTracer& tracer, const CameraView& cam,
                                             const Image& mirrorMask, glm::vec3 cellCentre) {
    std::vector<MirrorPixel> out;
    for (const ReflectorPixel& p : reflectorPixels(tracer, cam, mirrorMask))
        out.push_back({p.x, p.y, p.position - cellCentre, p.normal, p.lhat});
    return out;
}

// The reflector pass's mirror direction of the unit view ray v about n (mirrorDirection in
// reflector_common.glsl.h turns n towards the eye first; the reflection is the same, bit for
// bit, either way), unit.
inline glm::vec3 mirrorOf(glm::vec3 v, glm::vec3 n) {
    return glm::normalize(glm::reflect(v, n));
}

// A uniformly random unit vector (rejection from the unit ball).
inline glm::vec3 randomUnit(std::mt19937& rng) {
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    glm::vec3 d;
    do
        d = glm::vec3(u(rng), u(rng), u(rng));
    while (glm::dot(d, d) > 1.f || glm::dot(d, d) < 1e-4f);
    return glm::normalize(d);
}

class LightFieldGlossyRoom : public ::testing::Test {
protected:
    static constexpr int kWidth = 320, kHeight = 240;

    static void SetUpTestSuite() {
        scene_ = new ProbeRoom(kRoomScene, kRoomSky);
        LightFieldBakeOptions o;
        o.cellCentre = scene_->probeCentre();
        o.cellSize = scene_->cellSize();
        o.cameras = 8;
        o.res = 64;
        o.sky = &scene_->sky();
        asset_ = new LightFieldAsset(bakeLightFieldProbe(scene_->registry(), scene_->markup(), o));
        lf_ = new CpuLightFieldProbe(*asset_);
    }
    static void TearDownTestSuite() {
        delete lf_;
        delete asset_;
        delete scene_;
        lf_ = nullptr;
        asset_ = nullptr;
        scene_ = nullptr;
    }

    // The environment-only GGX truth of every reflector at roughness r, 256 samples a pixel.
    static TraceOptions ggxTruthOptions(float r) {
        TraceOptions o = groundTruthOptions(scene_->probeScene(), true);
        o.mirrorRoughness = [r](ecs::Entity, glm::vec2) { return r; };
        o.glossySamples = 256;
        return o;
    }

    static inline ProbeRoom* scene_ = nullptr;
    static inline LightFieldAsset* asset_ = nullptr;
    static inline CpuLightFieldProbe* lf_ = nullptr;
};

} // namespace specula::test
