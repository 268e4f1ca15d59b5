#pragma once
// The default room with its distance probe baked once per test binary (face resolution 128
// keeps the bake under a few seconds), a headless GL context, and a frame renderer.
// Components, engine and the cooking API only: no sandbox code.
#include "assetcooker/lib/bake/cook.h"
#include "components/reflection_probe/distance/distance_probe.h"
#include "components/reflection_probe/distance/system/distance_store.h"
#include "engine/context/context.h"
#include "engine/image_io/compare.h"
#include "support/probe_room.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>

namespace specula::test {

class RoomProbe : public ::testing::Test {
protected:
    static constexpr int kWidth = 320, kHeight = 240;

    static void SetUpTestSuite() {
        context_ = gpu::GlContext::createHeadless().release();
        scene_ = new ProbeRoom(kRoomScene, kRoomSky);
        dir_ = (std::filesystem::temp_directory_path() /
                ("specula-probe-test-" + std::to_string(::getpid())))
                   .string();
        // One layer per object, no plan recorded, through the cooking API.
        const char* faceRes = std::getenv("SPECULA_TEST_FACE_RES");
        DistanceCookSettings s;
        s.faceRes = faceRes ? std::atoi(faceRes) : 128;
        s.planned = s.recordPlan = false;
        CookOptions o;
        o.out = dir_;
        o.flavour = s;
        o.progress = false;
        cookProbe(scene_->probeScene(), o, nullptr);
        renderer_ = new RoomRenderer(*scene_, kWidth, kHeight);
    }
    static void TearDownTestSuite() {
        delete renderer_;
        delete scene_;
        delete context_;
        std::filesystem::remove_all(dir_);
    }

    static std::string manifest() { return dir_ + "/manifest.json"; }
    static DistanceProbe probeFor(DistanceMethod m, float de = 0.01f) {
        DistanceProbe p;
        p.method = m;
        p.errorTolerance = de;
        return p;
    }
    // Points the scene's probe at `asset` (the cooked room by default) with these settings.
    static void useProbe(const DistanceProbe& p, const std::string& asset = manifest()) {
        scene_->setProbe(asset, p);
    }

    static gpu::GlContext* context_;
    static ProbeRoom* scene_;
    static RoomRenderer* renderer_;
    static std::string dir_;
};

inline gpu::GlContext* RoomProbe::context_ = nullptr;
inline ProbeRoom* RoomProbe::scene_ = nullptr;
inline RoomRenderer* RoomProbe::renderer_ = nullptr;
inline std::string RoomProbe::dir_;

} // namespace specula::test
