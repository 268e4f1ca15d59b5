// A level's options checksum covers every setting of its flavour (issue 37 item 2): it is the
// settings as the shard list carries them (cookSettingsToJson), so a change of any one field
// marks every probe stale, "options changed". The level checksum used to be a hand-written
// text of some command-line flags, so a new plan seed or prefilter did not re-bake.
#include "assetcooker/lib/bake/cook_settings_json.h"
#include "assetcooker/lib/level/level_bake.h"
#include "support/scratch_dir_test.h"

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

namespace specula {
namespace {

const std::string kTwoRooms = std::string(SPECULA_SOURCE_DIR) + "/assets/two_rooms/two_rooms.gltf";

class LevelSettingsChecksum : public test::ScratchDirTest {
protected:
    LevelSettingsChecksum() : ScratchDirTest("specula-level-settings") {}

    LevelCookOptions options(const DistanceCookSettings& d) const {
        LevelCookOptions o;
        o.cook.scene = kTwoRooms;
        o.cook.out = (root_ / "level").string();
        o.cook.flavour = d;
        o.cook.progress = false;
        return o;
    }
};

DistanceCookSettings baseline() {
    DistanceCookSettings d;
    d.faceRes = 8;
    d.planned = false;
    d.glossy = GlossyBake::Off;
    return d;
}

TEST_F(LevelSettingsChecksum, EveryDistanceSettingMarksEveryProbeStale) {
    ProbeScene scene(kTwoRooms, "");
    const LevelCookResult first = cookLevel(scene, options(baseline()), nullptr);
    ASSERT_EQ(first.probes.size(), 2u);
    const LevelPlan same = planLevel(scene, options(baseline()), nullptr);
    for (const std::string& r : same.reasons)
        EXPECT_TRUE(r.empty()) << r; // up to date: the checksum is stable

    const std::vector<std::pair<const char*, std::function<void(DistanceCookSettings&)>>> edits = {
        {"face_res", [](DistanceCookSettings& d) { d.faceRes = 16; }},
        {"planned", [](DistanceCookSettings& d) { d.planned = true; }},
        {"record_plan", [](DistanceCookSettings& d) { d.recordPlan = false; }},
        {"measured_plan", [](DistanceCookSettings& d) { d.measuredPlan = false; }},
        {"max_error", [](DistanceCookSettings& d) { d.maxError = ErrorBudget{}; }},
        {"max_mib_per_probe", [](DistanceCookSettings& d) { d.maxMibPerProbe = 2.0; }},
        {"plan_seed", [](DistanceCookSettings& d) { d.planSeed = 7; }},
        {"glossy", [](DistanceCookSettings& d) { d.glossy = GlossyBake::On; }},
        {"prefilter.levels", [](DistanceCookSettings& d) { d.prefilter.levels = 4; }},
        {"prefilter.samples", [](DistanceCookSettings& d) { d.prefilter.samples += 8; }},
        {"prefilter.lod_bias", [](DistanceCookSettings& d) { d.prefilter.lodBias += 0.5f; }},
        {"compression", [](DistanceCookSettings& d) { d.compression = DistanceCompression::Bc6h; }},
    };
    for (const auto& [field, edit] : edits) {
        DistanceCookSettings d = baseline();
        edit(d);
        ASSERT_NE(cookSettingsToJson(d), cookSettingsToJson(baseline())) << field;
        const LevelPlan plan = planLevel(scene, options(d), nullptr);
        ASSERT_EQ(plan.reasons.size(), 2u) << field;
        for (const std::string& r : plan.reasons)
            EXPECT_NE(r.find("options changed"), std::string::npos) << field << ": " << r;
    }
}

} // namespace
} // namespace specula
