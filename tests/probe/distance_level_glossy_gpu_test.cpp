// Rough reflectors in a level of distance probes on the GPU (issue 14): the level shader's
// HAS_GLOSSY path against its CPU twin (CpuDistanceLevel at a roughness, the same shared blend
// and glossy code over the same chains) pixel by pixel; roughness 0 draws the level's mirror
// shader bit for bit; and a level pays for chains only while a reflector is rough (bytes and
// uploads counted by the store). The bundled two-room scene, its mirror moved into the
// doorway where both probes have influence.
#include "assetcooker/lib/level/level_bake.h"
#include "components/reflection_probe/distance/distance_level_cpu.h"
#include "components/reflection_probe/distance/distance_textures.h"
#include "components/reflection_probe/distance/system/distance_level_store.h"
#include "engine/context/context.h"
#include "engine/image_io/compare.h"
#include "support/probe_room.h"
#include "support/scratch_dir_test.h"
#include "twin_agreement.h"
#include "two_room_level_gpu_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace specula {
namespace {

const std::string& kTwoRooms = test::kTwoRoomsScene;
constexpr int kWidth = 160, kHeight = 120;
constexpr float kRoughness = 0.2f;

class LevelGlossyGpuTest : public test::TwoRoomLevelGpuTest {
protected:
    LevelGlossyGpuTest() : TwoRoomLevelGpuTest("specula-level-glossy-gpu") {}

    static void setRoughness(test::ProbeRoom& room, float r) {
        room.registry().view<Reflector>().each([&](ecs::Entity, Reflector& c) { c.roughness = r; });
    }
    static bool anyGlossy(const std::vector<std::string>& names) {
        return std::any_of(names.begin(), names.end(), [](const std::string& n) {
            return n.find("glossy") != std::string::npos;
        });
    }
    static bool samePixels(const Image& a, const Image& b) {
        return a.pixels.size() == b.pixels.size() &&
               std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
    }
};

// The twin runs on the shader's own inputs (world position, reflected direction, |n.v|, read
// back as float32) over chains equal to the store's, texel for texel; the shader's colour is
// divided by the GGX albedo it multiplied in (E from the C++ table at the read-back |n.v|).
TEST_F(LevelGlossyGpuTest, ShaderMatchesCpuTwinPerPixelForEveryBlend) {
    test::ProbeRoom room(kTwoRooms, "");
    const std::string index = bake(room);
    room.setReflectorOffset(glm::vec3(1.2f, 0.f, 0.f));
    const CameraView cam = doorwayCamera(kWidth, kHeight);
    const Image mask = erodedMask(room.groundTruth(cam, true).mirrorMask);
    test::RoomRenderer renderer(room, kWidth, kHeight);
    std::unique_ptr<CpuDistanceLevel> twin;
    for (const LevelBlend blend : {LevelBlend::Nearest, LevelBlend::Engine, LevelBlend::Visibility})
        for (const int k : {1, 4}) {
            DistanceLevel settings;
            settings.lookup.method = DistanceMethod::Secant;
            settings.blend = blend;
            settings.k = k;
            room.setProbe(index, settings);
            setRoughness(room, 0.f);
            const Image mirror = renderer.render(cam, 0);
            setRoughness(room, kRoughness);
            const Image colour = renderer.render(cam, 0);
            const std::vector<std::string> drawn = renderer.stats().permutations;
            const Image pos = renderer.render(cam, 1);
            const Image dir = renderer.render(cam, 2);
            const Image nv = renderer.render(cam, 3);
            if (!twin) twin = std::make_unique<CpuDistanceLevel>(index, settings.lookup, true);
            const DistanceLevelStore& store = *renderer.probes().store<DistanceLevelStore>();
            const auto* chains = store.glossyChains(room.probeEntity());
            ASSERT_TRUE(chains && chains->size() == 2) << "a rough reflector drew: two chains";
            for (int i = 0; i < 2; ++i)
                for (std::size_t l = 0; l < (*chains)[std::size_t(i)]->levels.size(); ++l)
                    ASSERT_EQ((*chains)[std::size_t(i)]->levels[l][0].pixels,
                              twin->glossyChain(i)->levels[l][0].pixels)
                        << "probe " << i << " level " << l;
            const Image lighting = test::withoutGgxAlbedo(colour, nv, mask, kRoughness);
            double fromMirror = 0.0;
            for (int y = 0; y < mask.height; ++y)
                for (int x = 0; x < mask.width; ++x)
                    if (mask.at(x, y)[0] >= 0.5f)
                        fromMirror += glm::length(glm::vec3(colour.rgba(x, y) - mirror.rgba(x, y)));
            long blended = 0;
            const test::PixelAgreement a = test::agreeByPixel(
                lighting, pos, dir, mask,
                [&](glm::vec3 p, glm::vec3 l) {
                    const LevelSample s = twin->radiance(p, l, blend, k, kRoughness);
                    blended += s.weights.size() >= 2 ? 1 : 0;
                    return s.radiance;
                },
                2e-3);
            fromMirror /= double(std::max(a.n, 1L));
            std::printf("%-10s K=%d r %.1f: %ld px (%ld blend 2+ probes), %.2f%% within 2e-3, "
                        "mean %.2e, worst %.4f; mean change from the mirror %.4f\n",
                        toString(blend), k, kRoughness, a.n, blended, 100.0 * a.share(), a.mean(),
                        a.worst, fromMirror);
            ASSERT_GT(a.n, 1000) << "the camera must see the mirror";
            EXPECT_GT(a.colourSum / double(a.n), 0.02) << "the level draws something";
            EXPECT_TRUE(anyGlossy(drawn));
            EXPECT_GT(fromMirror, 5e-3) << "the glossy path ran";
            if (blend == LevelBlend::Engine && k > 1) {
                EXPECT_GT(blended, a.n / 10);
            }
            // As for the mirror level: a nearest distance fetch on a texel boundary may end a
            // search a texel apart between GPU and CPU.
            EXPECT_GT(a.share(), 0.99) << toString(blend) << " K=" << k;
            EXPECT_LT(a.mean(), 1e-3) << toString(blend) << " K=" << k;
        }
}

// Roughness 0 draws the level's mirror shader, bit for bit, before and after a rough frame;
// a level whose reflectors are all mirrors holds no chain and uploads none (its bytes are
// the composites' and the sky's alone); the first rough reflector makes every probe's chain
// in sync (one upload, counted in the bytes), outside the drawn frame.
TEST_F(LevelGlossyGpuTest, MirrorsDrawTheMirrorShaderAndUploadNoChain) {
    test::ProbeRoom room(kTwoRooms, "");
    setUpSecantDoorway(room);
    const CameraView cam = doorwayCamera(kWidth, kHeight);
    test::RoomRenderer renderer(room, kWidth, kHeight);
    setRoughness(room, 0.f);
    const Image before = renderer.render(cam);
    const std::vector<std::string> mirrorNames = renderer.stats().permutations;
    ReflectionProbeSystem& system = renderer.probes();
    const DistanceLevelStore& store = *system.store<DistanceLevelStore>();
    ASSERT_TRUE(store.glossyChains(room.probeEntity()));
    EXPECT_TRUE(store.glossyChains(room.probeEntity())->empty()) << "mirrors: no chain";
    const std::size_t mirrorBytes = system.stats().probeGpuBytes;
    const std::size_t uploads = system.stats().textureUploads;
    const DistanceLevelGpu* g = store.probe(room.probeEntity());
    ASSERT_TRUE(g);
    const DistanceProbeAsset& first = *g->assets.front();
    const std::size_t composites = cubeArrayBytes(first.faceRes, 2);
    const std::size_t sky = first.sky.empty() ? 0 : skyTextureBytes(first.sky);
    EXPECT_EQ(mirrorBytes, composites + sky) << "a mirror level holds its composites and sky";

    setRoughness(room, kRoughness);
    system.sync(room.registry());
    const auto& chains = *store.glossyChains(room.probeEntity());
    ASSERT_EQ(chains.size(), 2u);
    const std::size_t chainBytes = chainArrayBytes(*chains.front());
    EXPECT_EQ(system.stats().textureUploads, uploads + 1);
    EXPECT_EQ(system.stats().probeGpuBytes, mirrorBytes + 2 * chainBytes);
    const Image rough = renderer.render(cam);
    const std::vector<std::string> roughNames = renderer.stats().permutations;
    EXPECT_EQ(system.stats().textureUploads, uploads + 1) << "nothing more uploaded";
    std::printf("two-room level, 64^2 faces: mirror %zu bytes (composites %zu, sky %zu), rough "
                "%zu bytes (+%zu: 2 chains of %zu)\n",
                mirrorBytes, composites, sky, system.stats().probeGpuBytes,
                system.stats().probeGpuBytes - mirrorBytes, chainBytes);

    setRoughness(room, 0.f);
    const Image after = renderer.render(cam);
    const std::vector<std::string> afterNames = renderer.stats().permutations;
    EXPECT_FALSE(anyGlossy(mirrorNames));
    EXPECT_FALSE(anyGlossy(afterNames));
    EXPECT_TRUE(anyGlossy(roughNames));
    EXPECT_EQ(afterNames, mirrorNames);
    EXPECT_TRUE(samePixels(before, after));
    EXPECT_FALSE(samePixels(before, rough));
}

} // namespace
} // namespace specula
