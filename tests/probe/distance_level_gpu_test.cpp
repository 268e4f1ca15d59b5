// A level of distance probes drawn on the GPU (DistanceLevelStore,
// shaders/distance_level_reflector.frag) against its CPU twin (CpuDistanceLevel), on the
// bundled two-room scene with the mirror moved into the doorway, where both probes have
// influence: pixel by pixel, for every blend and for K = 1 and 4. And the level's limits:
// more probes than one view holds, and settings a level cannot run, are errors that name
// the file and the field.
#include "assetcooker/lib/level/level_bake.h"
#include "components/reflection_probe/distance/distance_level_cpu.h"
#include "components/reflection_probe/distance/system/distance_level_store.h"
#include "engine/context/context.h"
#include "engine/core/error.h"
#include "engine/core/file_write.h"
#include "engine/image_io/compare.h"
#include "support/probe_room.h"
#include "support/scratch_dir_test.h"
#include "twin_agreement.h"
#include "two_room_level_gpu_fixture.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>

namespace specula {
namespace {

const std::string& kTwoRooms = test::kTwoRoomsScene;
constexpr int kWidth = 160, kHeight = 120;

class DistanceLevelGpuTest : public test::TwoRoomLevelGpuTest {
protected:
    DistanceLevelGpuTest() : TwoRoomLevelGpuTest("specula-level-gpu") {}
};

TEST_F(DistanceLevelGpuTest, ShaderMatchesCpuTwinPerPixelForEveryBlend) {
    test::ProbeRoom room(kTwoRooms, "");
    const std::string index = bake(room);
    // The mirror sphere (authored at x = -1 in room A) moved into the doorway (the wall at
    // x = 0), where both probes' influence volumes rise over their blend distances.
    room.setReflectorOffset(glm::vec3(1.2f, 0.f, 0.f));
    const CameraView cam = doorwayCamera(kWidth, kHeight);
    const Image mask = erodedMask(room.groundTruth(cam, true).mirrorMask);
    test::RoomRenderer renderer(room, kWidth, kHeight);
    for (const LevelBlend blend : {LevelBlend::Nearest, LevelBlend::Engine, LevelBlend::Visibility})
        for (const int k : {1, 4}) {
            DistanceLevel settings;
            settings.lookup.method = DistanceMethod::Secant;
            settings.blend = blend;
            settings.k = k;
            room.setProbe(index, settings);
            const Image colour = renderer.render(cam, 0);
            const Image pos = renderer.render(cam, 1);
            const Image dir = renderer.render(cam, 2);
            ASSERT_FALSE(renderer.stats().permutations.empty());
            const CpuDistanceLevel twin(index, settings.lookup);
            long blended = 0;
            const test::PixelAgreement a = test::agreeByPixel(
                colour, pos, dir, mask,
                [&](glm::vec3 p, glm::vec3 l) {
                    const LevelSample s = twin.radiance(p, l, blend, k);
                    blended += s.weights.size() >= 2 ? 1 : 0;
                    return s.radiance;
                },
                2e-3);
            std::printf("%-10s K=%d: %ld mirror px (%ld blend 2+ probes), %.2f%% within 2e-3, "
                        "mean %.2e, worst %.4f\n",
                        toString(blend), k, a.n, blended, 100.0 * a.share(), a.mean(), a.worst);
            ASSERT_GT(a.n, 1000) << "the camera must see the mirror";
            EXPECT_GT(a.colourSum / double(a.n), 0.02) << "the level draws something";
            if (blend == LevelBlend::Engine && k > 1) {
                EXPECT_GT(blended, a.n / 10) << "the doorway must blend both probes";
                // (Visibility drops the probe that does not see the hit: fewer blend.)
            }
            // A nearest distance fetch on a texel boundary can flip on the last bit of a float
            // between GPU and CPU and end a search one texel apart: allow 1 % of pixels.
            EXPECT_GT(a.share(), 0.99) << toString(blend) << " K=" << k;
            EXPECT_LT(a.mean(), 1e-3) << toString(blend) << " K=" << k;
        }
}

TEST_F(DistanceLevelGpuTest, MoreProbesThanOneViewHoldsIsAnErrorWithTheLimit) {
    test::ProbeRoom room(kTwoRooms, "");
    const std::string index = bake(room);
    std::ifstream in(index);
    nlohmann::json level = nlohmann::json::parse(in);
    const nlohmann::json first = level["probes"][0];
    level["probes"] = nlohmann::json::array();
    for (int i = 0; i <= glsl::kMaxLevelProbes; ++i) {
        nlohmann::json p = first;
        p["name"] = "copy_" + std::to_string(i);
        level["probes"].push_back(p);
    }
    const std::string big = (root_ / "level" / "big_level.json").string();
    writeFileAtomically(big, level.dump(1));
    room.setProbe(big, DistanceLevel{});
    test::RoomRenderer renderer(room, kWidth, kHeight);
    try {
        renderer.render(room.camera(kWidth, kHeight));
        FAIL() << "a level of " << glsl::kMaxLevelProbes + 1 << " probes drew";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("big_level.json"), std::string::npos) << what;
        EXPECT_NE(what.find("probes"), std::string::npos) << what;
        EXPECT_NE(what.find("at most " + std::to_string(maxLevelProbes())), std::string::npos)
            << what;
    }
}

TEST_F(DistanceLevelGpuTest, SettingsALevelCannotRunAreErrorsNamingTheField) {
    test::ProbeRoom room(kTwoRooms, "");
    const std::string index = bake(room);
    test::RoomRenderer renderer(room, kWidth, kHeight);
    DistanceLevel layered;
    layered.lookup.method = DistanceMethod::Layered;
    DistanceLevel tooMany;
    tooMany.k = glsl::kMaxLevelK + 1;
    for (const auto& [settings, field] : {std::pair{layered, "method"}, std::pair{tooMany, "k"}}) {
        room.setProbe(index, settings);
        try {
            renderer.render(room.camera(kWidth, kHeight));
            FAIL() << field << " was accepted";
        } catch (const Error& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("level.json"), std::string::npos) << what;
            EXPECT_NE(what.find(field), std::string::npos) << what;
        }
    }
}

} // namespace
} // namespace specula
