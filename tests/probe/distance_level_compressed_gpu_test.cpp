// A level of compressed probes on the GPU (issue 36, item 3): every probe cooked with
// --compress bc6h, their radiance in one BC6H array and their distances in another, drawn
// through the level's COMPRESSED_COMPOSITE permutation, agrees pixel by pixel with its CPU
// twin (which reads the decoded values), in the doorway where both probes blend.
#include "components/reflection_probe/distance/distance_level_cpu.h"
#include "components/reflection_probe/distance/distance_textures.h"
#include "components/reflection_probe/distance/system/distance_level_store.h"
#include "twin_agreement.h"
#include "two_room_level_gpu_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

namespace specula {
namespace {

constexpr int kWidth = 160, kHeight = 120;

class CompressedLevelGpuTest : public test::TwoRoomLevelGpuTest {
protected:
    CompressedLevelGpuTest() : TwoRoomLevelGpuTest("specula-level-bc6h") {}
};

TEST_F(CompressedLevelGpuTest, ShaderMatchesCpuTwinOnTheDecodedValues) {
    test::ProbeRoom room(test::kTwoRoomsScene, "");
    const std::string index = bake(room, DistanceCompression::Bc6h);
    room.setReflectorOffset(glm::vec3(1.2f, 0.f, 0.f));
    const CameraView cam = doorwayCamera(kWidth, kHeight);
    const Image mask = erodedMask(room.groundTruth(cam, true).mirrorMask);
    test::RoomRenderer renderer(room, kWidth, kHeight);
    for (const LevelBlend blend : {LevelBlend::Engine, LevelBlend::Visibility}) {
        DistanceLevel settings;
        settings.lookup.method = DistanceMethod::Secant;
        settings.blend = blend;
        settings.k = 4;
        room.setProbe(index, settings);
        const Image colour = renderer.render(cam, 0);
        const Image pos = renderer.render(cam, 1);
        const Image dir = renderer.render(cam, 2);
        const std::vector<std::string>& drawn = renderer.stats().permutations;
        EXPECT_TRUE(std::any_of(drawn.begin(), drawn.end(), [](const std::string& v) {
            return v.find("bc6h") != std::string::npos;
        })) << "the compressed permutation must be drawn";
        const CpuDistanceLevel twin(index, settings.lookup);
        const test::PixelAgreement a = test::agreeByPixel(
            colour, pos, dir, mask,
            [&](glm::vec3 p, glm::vec3 l) { return twin.radiance(p, l, blend, 4).radiance; }, 2e-3);
        std::printf("%-10s bc6h: %ld mirror px, %.2f%% within 2e-3, mean %.2e, worst %.4f\n",
                    toString(blend), a.n, 100.0 * a.share(), a.mean(), a.worst);
        ASSERT_GT(a.n, 1000) << "the camera must see the mirror";
        EXPECT_GT(a.colourSum / double(a.n), 0.02) << "the level draws something";
        // The float level's bounds (distance_level_gpu_test.cpp).
        EXPECT_GT(a.share(), 0.99) << toString(blend);
        EXPECT_LT(a.mean(), 1e-3) << toString(blend);
    }
}

// Probes cooked compressed with their glossy levels: the level's one chain array is BC6H,
// uploaded from every probe's blocks, and the HAS_GLOSSY shader sampling it agrees with the
// twin reading their decoding as the float level's does (distance_level_glossy_gpu_test.cpp).
TEST_F(CompressedLevelGpuTest, TheGlossyChainsAreSampledFromTheirBlocks) {
    constexpr float kRoughness = 0.2f;
    test::ProbeRoom room(test::kTwoRoomsScene, "");
    const std::string index = bake(room, DistanceCompression::Bc6h, GlossyBake::On);
    room.setReflectorOffset(glm::vec3(1.2f, 0.f, 0.f));
    const CameraView cam = doorwayCamera(kWidth, kHeight);
    const Image mask = erodedMask(room.groundTruth(cam, true).mirrorMask);
    test::RoomRenderer renderer(room, kWidth, kHeight);
    DistanceLevel settings;
    settings.lookup.method = DistanceMethod::Secant;
    settings.blend = LevelBlend::Engine;
    settings.k = 4;
    room.setProbe(index, settings);
    const auto setRoughness = [&](float r) {
        room.registry().view<Reflector>().each([&](ecs::Entity, Reflector& c) { c.roughness = r; });
    };
    setRoughness(0.f);
    renderer.render(cam, 0);
    const std::size_t mirrorBytes = renderer.probes().stats().probeGpuBytes;
    setRoughness(kRoughness);
    const Image colour = renderer.render(cam, 0);
    const Image pos = renderer.render(cam, 1);
    const Image dir = renderer.render(cam, 2);
    const Image nv = renderer.render(cam, 3);
    const std::size_t roughBytes = renderer.probes().stats().probeGpuBytes;
    setRoughness(0.f);
    const CpuDistanceLevel twin(index, settings.lookup, true);
    ASSERT_EQ(twin.volumes().size(), 2u);
    const Image lighting = test::withoutGgxAlbedo(colour, nv, mask, kRoughness);
    const test::PixelAgreement a = test::agreeByPixel(
        lighting, pos, dir, mask,
        [&](glm::vec3 p, glm::vec3 l) {
            return twin.radiance(p, l, settings.blend, settings.k, kRoughness).radiance;
        },
        2e-3);
    const CubeChain& chain = *twin.glossyChain(0);
    std::printf("engine K=4 r %.1f, BC6H chains: %ld px, %.2f%% within 2e-3, mean %.2e, "
                "worst %.4f; chains %zu bytes on the GPU (%zu as RGBA32F)\n",
                kRoughness, a.n, 100.0 * a.share(), a.mean(), a.worst, roughBytes - mirrorBytes,
                2 * chainArrayBytes(chain));
    ASSERT_GT(a.n, 1000) << "the camera must see the mirror";
    EXPECT_GT(a.share(), 0.99);
    EXPECT_LT(a.mean(), 1e-3);
    EXPECT_EQ(roughBytes - mirrorBytes, 2 * chainArrayBytes(chain, true)) << "two BC6H chains";
}

} // namespace
} // namespace specula
