// The sandbox's ground truth follows the reflectors as they are drawn (issue 14): a mirror
// scene traces the mirror truth exactly as before, a reflector made rough (walk --roughness)
// is traced GGX-sampled at its roughness, and one with a roughness map at its map's value at
// each hit. Each against a GroundTruthTracer given the same roughness explicitly, bit for bit.
#include "assetcooker/lib/scene/probe_setup.h"
#include "components/reflection_probe/system/reflection_probe.h"
#include "components/reflection_probe/system/reflector_roughness.h"
#include "sandbox/lib/render/reflection_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

using namespace specula;

namespace {

const std::string kRoom = SPECULA_SOURCE_DIR "/assets/room/room.gltf";
const std::string kBands = SPECULA_SOURCE_DIR "/assets/room/room_rough_bands.gltf";
constexpr int kW = 96, kH = 72, kSamples = 16;

// The largest per-channel difference over the frame.
float largestDifference(const Image& a, const Image& b) {
    float worst = 0.f;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        worst = std::max(worst, std::abs(a.pixels[i] - b.pixels[i]));
    return worst;
}

// The truth traced with the roughness given explicitly: the independent reference.
Image explicitTruth(ReflectionScene& scene, const CameraView& cam,
                    std::function<float(ecs::Entity, glm::vec2)> roughness) {
    TraceOptions o = groundTruthOptions(scene.probeScene(), true);
    o.mirrorRoughness = std::move(roughness);
    o.glossySamples = kSamples;
    return GroundTruthTracer(scene.registry(), o).render(cam).color;
}

} // namespace

TEST(ReflectionSceneTruth, FollowsTheDrawnRoughness) {
    ReflectionScene scene(kRoom, defaultSkyPath());
    attachProbeComponents(scene.registry(), scene.markup(), ReflectionProbe{"unused.json"});
    scene.setGlossyTruthSamples(kSamples);
    const CameraView cam = scene.camera(kW, kH);
    const Image mirror = scene.groundTruth(cam, true).color;
    // Mirrors: the mirror path, as traceGroundTruth has always traced it.
    EXPECT_EQ(largestDifference(mirror, traceGroundTruth(scene.probeScene(), cam, true).color),
              0.f);

    scene.setReflectorRoughness(0.2f);
    const Image rough = scene.groundTruth(cam, true).color;
    EXPECT_EQ(largestDifference(
                  rough, explicitTruth(scene, cam, [](ecs::Entity, glm::vec2) { return 0.2f; })),
              0.f);
    // And it is a different picture from the mirror's.
    const float changed = largestDifference(rough, mirror);
    std::printf("roughness 0.2 against the mirror truth: largest difference %.3f\n", changed);
    EXPECT_GT(changed, 0.1f);

    scene.setReflectorRoughness(0.f);
    EXPECT_EQ(largestDifference(scene.groundTruth(cam, true).color, mirror), 0.f);
}

TEST(ReflectionSceneTruth, ReadsARoughnessMapAtEachHit) {
    ReflectionScene scene(kBands, defaultSkyPath());
    attachProbeComponents(scene.registry(), scene.markup(), ReflectionProbe{"unused.json"});
    scene.setGlossyTruthSamples(kSamples);
    const CameraView cam = scene.camera(kW, kH);
    const std::shared_ptr<const Image> map = scene.markup().reflectors.front().roughnessMap;
    ASSERT_TRUE(map);
    const Image banded = scene.groundTruth(cam, true).color;
    const Image* m = map.get();
    EXPECT_EQ(largestDifference(banded, explicitTruth(scene, cam,
                                                      [m](ecs::Entity, glm::vec2 uv) {
                                                          return roughnessAt(1.f, m, uv);
                                                      })),
              0.f);
    // Not the map's mean, uniform.
    const float mean = 61.f / 255.f;
    const float fromMean = largestDifference(
        banded, explicitTruth(scene, cam, [mean](ecs::Entity, glm::vec2) { return mean; }));
    std::printf("the banded truth against the map's mean: largest difference %.3f\n", fromMean);
    EXPECT_GT(fromMean, 0.05f);
}
