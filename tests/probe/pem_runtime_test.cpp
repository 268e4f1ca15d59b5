// The runtime side of the parameterized-environment-map flavour: the asset's write/read
// round trip (box and distance geometry) and what the reader refuses, the blend weights, the shader
// against its CPU twin on the default room (at a sample and between two), and a parameter edit that
// uploads the parameter block only. Components, engine and cooker only: no sandbox code.
#include "assetcooker/lib/flavours/pem/pem_geometry.h"
#include "assetcooker/lib/scene/probe_setup.h"
#include "components/reflection_probe/pem/pem_asset.h"
#include "components/reflection_probe/pem/pem_blend.h"
#include "components/reflection_probe/pem/pem_probe_cpu.h"
#include "components/reflection_probe/pem/system/pem_store.h"
#include "components/reflection_probe/pem/writer/pem_probe_writer.h"
#include "engine/context/context.h"
#include "engine/core/error.h"
#include "engine/image/ktx2.h"
#include "engine/image_io/compare.h"
#include "engine/image_io/image_io.h"
#include "engine/raytrace/ground_truth.h"
#include "engine/scene/mesh_bounds.h"
#include "pem/pem_files_fixture.h"
#include "pem/pem_random_asset.h"
#include "support/probe_room.h"
#include "support/scratch_dir_test.h"
#include "twin_agreement.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <random>

using namespace specula;
using nlohmann::json;
using specula::test::addDistanceGeometry;
using specula::test::randomAsset;
namespace fs = std::filesystem;

namespace {

class PemAssetFiles : public test::PemFilesTest {
protected:
    PemAssetFiles() : PemFilesTest("specula-pem-asset") {}

    std::string sampleFile(int k) const {
        return dir() + "/sample_0" + std::to_string(k) + ".ktx2";
    }
};

} // namespace

TEST_F(PemAssetFiles, RoundTripKeepsEveryFieldAndTexel) {
    PemAsset a = randomAsset(4, 3, glm::vec3(-2.f, -1.f, -3.f), glm::vec3(2.f, 3.f, 1.f));
    a.imageWidth = 320, a.imageHeight = 240;
    writePemProbe(a, dir(), "analytic");
    const PemAsset b = readPemProbe(manifest());
    EXPECT_EQ(b.imageWidth, 320);
    EXPECT_EQ(b.imageHeight, 240);
    EXPECT_EQ(b.manifestPath, manifest());
    EXPECT_EQ(b.centre, a.centre);
    EXPECT_EQ(b.parameterKind, "reflector");
    EXPECT_EQ(b.path, "line");
    EXPECT_EQ(b.faceRes, 4);
    EXPECT_EQ(b.boxMin, a.boxMin);
    EXPECT_EQ(b.boxMax, a.boxMax);
    ASSERT_EQ(b.samples.size(), 3u);
    for (std::size_t k = 0; k < 3; ++k) {
        EXPECT_EQ(b.samples[k].parameter, a.samples[k].parameter);
        EXPECT_EQ(b.samples[k].map.faceRes, 4);
        EXPECT_EQ(b.samples[k].map.boxMin, a.boxMin);
        EXPECT_EQ(b.samples[k].map.texels, a.samples[k].map.texels) << "sample " << k;
        EXPECT_EQ(b.samples[k].file, "sample_0" + std::to_string(k) + ".ktx2");
        EXPECT_EQ(b.samples[k].checksum, fileChecksum(sampleFile(int(k))));
    }
}

TEST_F(PemAssetFiles, WriterRefusesWhatTheReaderWould) {
    PemAsset a = randomAsset(4, 3, glm::vec3(-1.f), glm::vec3(1.f));
    auto refused = [&](const std::string& fileSuffix, const std::string& field) {
        try {
            writePemProbe(a, dir(), "analytic");
            ADD_FAILURE() << "expected " << field << " to be refused";
        } catch (const Error& e) {
            EXPECT_TRUE(e.file().ends_with(fileSuffix)) << e.what();
            EXPECT_EQ(e.field(), field) << e.what();
        }
        EXPECT_FALSE(fs::exists(dir())) << "nothing is written on failure";
    };
    a.samples[1].map.texels[5].g = NAN;
    refused("sample_01.ktx2", "radiance");
    a.samples[1].map.texels[5].g = 0.5f;
    a.samples[2].parameter = 0.5f; // equal to sample 1's
    refused("manifest.json", "samples[2].parameter");
    a.samples[2].parameter = 1.f;
    a.samples[0].map.faceRes = 8;
    refused("manifest.json", "samples[0].map");
    a.samples[0].map.faceRes = 4;
    a.parameterKind = "time";
    refused("manifest.json", "parameter_kind");
}

TEST_F(PemAssetFiles, ReaderRefusesBadInputNamingFileAndField) {
    const PemAsset a = randomAsset(4, 3, glm::vec3(-1.f), glm::vec3(1.f));
    auto rewrite = [&] {
        fs::remove_all(dir());
        writePemProbe(a, dir(), "analytic");
    };
    rewrite();
    fs::remove(sampleFile(1));
    expectRefused("manifest.json", "samples[1].file");

    rewrite();
    editManifest([](json& m) { m["samples"][0]["checksum"] = "fnv1a64:0000000000000000"; });
    expectRefused("manifest.json", "samples[0].checksum");

    rewrite(); // a NaN texel, checksum updated so that the content check is reached
    Image img = readKtx2(sampleFile(2)).levels[0];
    img.at(3, 9)[1] = NAN;
    writeKtx2Cube(sampleFile(2), img);
    editManifest([&](json& m) { m["samples"][2]["checksum"] = fileChecksum(sampleFile(2)); });
    expectRefused("sample_02.ktx2", "radiance");

    rewrite();
    editManifest([](json& m) { m["samples"][2]["parameter"] = 0.25; });
    expectRefused("manifest.json", "samples[2].parameter");

    rewrite();
    editManifest([](json& m) { m["samples"][0]["parameter"] = 1.5; });
    expectRefused("manifest.json", "samples[0].parameter");

    rewrite();
    editManifest([](json& m) { m["flavour"] = "distance"; });
    expectRefused("manifest.json", "flavour");

    rewrite();
    editManifest([](json& m) { m["face_res"] = 8; }); // the images are 4 x 24
    expectRefused("manifest.json", "samples[0].file");

    rewrite();
    editManifest([](json& m) { m["image_size"] = {0, 240}; });
    expectRefused("manifest.json", "image_size.w");
    rewrite();
    editManifest([](json& m) { m["image_size"] = 640; });
    expectRefused("manifest.json", "image_size");
}

TEST_F(PemAssetFiles, DistanceGeometryRoundTrips) {
    PemAsset a = randomAsset(4, 2, glm::vec3(-1.f), glm::vec3(1.f));
    addDistanceGeometry(a, 6);
    writePemProbe(a, dir(), "analytic");
    const PemAsset b = readPemProbe(manifest());
    EXPECT_EQ(b.geometry, "distance");
    ASSERT_NE(b.distance, nullptr);
    EXPECT_EQ(*b.distance, *a.distance); // distances, d_inf, range, tolerance, steps
    EXPECT_EQ(b.distanceFile, "distance.ktx2");
    EXPECT_EQ(b.distanceChecksum, fileChecksum(dir() + "/distance.ktx2"));
    const Image img = readKtx2(dir() + "/distance.ktx2").levels[0];
    EXPECT_EQ(img.width, 6);
    EXPECT_EQ(img.height, 36);
    for (const PemSampleMap& s : b.samples)
        EXPECT_EQ(s.map.distance, b.distance) << "every map shares the asset's geometry";
}

// A box PEM written before distance geometry existed has no "geometry" field.
TEST_F(PemAssetFiles, ManifestWithoutGeometryReadsAsBox) {
    writePemProbe(randomAsset(4, 2, glm::vec3(-1.f), glm::vec3(1.f)), dir(), "analytic");
    editManifest([](json& m) {
        EXPECT_EQ(m["geometry"], "box");
        m.erase("geometry");
        m.erase("seal"); // nor a seal
    });
    const PemAsset b = readPemProbe(manifest());
    EXPECT_EQ(b.geometry, "box");
    EXPECT_EQ(b.distance, nullptr);
    EXPECT_EQ(b.samples[0].map.distance, nullptr);
}

TEST_F(PemAssetFiles, ReaderRefusesBadDistanceGeometryNamingFileAndField) {
    PemAsset a = randomAsset(4, 2, glm::vec3(-1.f), glm::vec3(1.f));
    addDistanceGeometry(a, 6);
    auto rewrite = [&] {
        fs::remove_all(dir());
        writePemProbe(a, dir(), "analytic");
    };
    const std::string distanceFile = dir() + "/distance.ktx2";
    rewrite(); // tampered pixels: the checksum no longer matches
    Image img = readKtx2(distanceFile).levels[0];
    img.at(2, 11)[0] += 1.f;
    writeKtx2Cube(distanceFile, img);
    expectRefused("manifest.json", "distance.checksum");

    for (const float bad : {float(NAN), -1.f, 0.f, 2000.f}) {
        rewrite(); // checksum updated, so that the content check is reached
        img = readKtx2(distanceFile).levels[0];
        img.at(2, 11)[0] = bad;
        writeKtx2Cube(distanceFile, img);
        editManifest([&](json& m) { m["distance"]["checksum"] = fileChecksum(distanceFile); });
        expectRefused("distance.ktx2", "distance");
    }

    rewrite();
    fs::remove(distanceFile);
    expectRefused("manifest.json", "distance.file");

    rewrite();
    editManifest([](json& m) { m["distance"]["face_res"] = 5; }); // the image is 6 x 36
    expectRefused("manifest.json", "distance.file");

    for (const char* field : {"face_res", "d_inf", "range", "tolerance", "max_steps"}) {
        rewrite();
        editManifest([&](json& m) { m["distance"].erase(field); });
        expectRefused("manifest.json", std::string("distance.") + field);
    }
    rewrite();
    editManifest([](json& m) { m["distance"]["range"] = 600.0; }); // past d_inf / 2
    expectRefused("manifest.json", "distance.range");

    rewrite();
    editManifest([](json& m) { m.erase("distance"); });
    expectRefused("manifest.json", "distance");

    rewrite();
    editManifest([](json& m) { m["geometry"] = "sphere"; });
    expectRefused("manifest.json", "geometry");

    // The writer refuses a sample map whose geometry is not the asset's.
    PemAsset mixed = a;
    mixed.samples[1].map.distance = nullptr;
    fs::remove_all(dir());
    try {
        writePemProbe(mixed, dir(), "analytic");
        ADD_FAILURE() << "expected samples[1].map to be refused";
    } catch (const Error& e) {
        EXPECT_EQ(e.field(), "samples[1].map") << e.what();
    }
}

TEST(PemBlend, ContinuousExactAtSamplesClampedAtTheEnds) {
    const std::vector<float> params = {0.1f, 0.3f, 0.45f, 0.8f}; // gaps >= 0.15
    // A blend's weight on each sample: continuity is about these, not about (a, b, wb).
    auto weights = [&](float t) {
        const PemBlendWeights w = pemBlend(params, t, false);
        std::vector<float> out(params.size(), 0.f);
        out[std::size_t(w.a)] += 1.f - w.wb;
        out[std::size_t(w.b)] += w.wb;
        return out;
    };
    float worstJump = 0.f;
    std::vector<float> prev = weights(0.f);
    for (int i = 1; i <= 1000; ++i) {
        const std::vector<float> cur = weights(float(i) / 1000.f);
        for (std::size_t k = 0; k < params.size(); ++k)
            worstJump = std::max(worstJump, std::fabs(cur[k] - prev[k]));
        prev = cur;
    }
    std::printf("pemBlend: largest weight change between parameters 1/1000 apart: %.4f\n",
                worstJump);
    EXPECT_LT(worstJump, 0.01f); // linear: at most 1/1000 over the smallest gap, 0.0067
    for (std::size_t k = 0; k < params.size(); ++k) {
        const std::vector<float> w = weights(params[k]);
        EXPECT_EQ(w[k], 1.f) << "exact at sample " << k;
    }
    EXPECT_EQ(pemBlend(params, 0.f, false), (PemBlendWeights{0, 0, 0.f}));
    EXPECT_EQ(pemBlend(params, 1.f, false), (PemBlendWeights{3, 3, 0.f}));
    EXPECT_EQ(pemBlend(params, NAN, false), (PemBlendWeights{0, 0, 0.f}));
    const PemBlendWeights mid = pemBlend(params, 0.2f, false);
    EXPECT_EQ(mid.a, 0);
    EXPECT_EQ(mid.b, 1);
    EXPECT_NEAR(mid.wb, 0.5f, 1e-6f);
    EXPECT_EQ(pemBlend({0.5f}, 0.7f, false), (PemBlendWeights{0, 0, 0.f}));
}

TEST(PemBlend, NearestModePicksTheNearerSampleAlone) {
    const std::vector<float> params = {0.f, 0.5f, 1.f};
    EXPECT_EQ(pemBlend(params, 0.2f, true), (PemBlendWeights{0, 0, 0.f}));
    EXPECT_EQ(pemBlend(params, 0.3f, true), (PemBlendWeights{1, 1, 0.f}));
    EXPECT_EQ(pemBlend(params, 0.74f, true), (PemBlendWeights{1, 1, 0.f}));
    EXPECT_EQ(pemBlend(params, 0.76f, true), (PemBlendWeights{2, 2, 0.f}));
    EXPECT_EQ(pemBlend(params, 1.f, true), (PemBlendWeights{2, 2, 0.f}));
    EXPECT_EQ(kPemMethods[0].label.name, std::string("pem"));
    EXPECT_EQ(kPemMethods[1].label.name, std::string("pem-nearest"));
    EXPECT_TRUE(kPemMethods[1].nearest);
}

namespace {

// The default room with a PEM probe of three random 16^2 maps whose box encloses the
// reflectors (distance: plus the room's distance cube, 64^2, baked with Embree as the cooker
// does), a headless context and a renderer (built-in flavours: PEM included). Everything a
// PemRoom test draws with, made once per suite; members are destroyed in reverse, so the GL
// objects go before the context.
struct PemRoomState {
    static constexpr int kWidth = 200, kHeight = 150;

    std::unique_ptr<gpu::GlContext> context = gpu::GlContext::createHeadless();
    test::ProbeRoom scene{test::kRoomScene, test::kRoomSky};
    test::RoomRenderer renderer{scene, kWidth, kHeight};
    std::string manifest;
    fs::path dir = fs::temp_directory_path() / ("specula-pem-room-" + std::to_string(::getpid()));

    explicit PemRoomState(bool distance) {
        const glm::vec3 centre = scene.probeCentre();
        Aabb box;
        for (const ReflectorMarkup& r : scene.markup().reflectors)
            for (ecs::Entity mesh : r.meshes)
                box.extend(meshWorldBoundsConservative(scene.registry(), mesh));
        PemAsset a = randomAsset(16, 3, box.min - centre - 0.5f, box.max - centre + 0.5f);
        a.centre = centre;
        if (distance) {
            const GroundTruthTracer tracer(scene.registry(),
                                           groundTruthOptions(scene.probeScene(), true));
            a.geometry = "distance";
            a.distance = std::make_shared<PemDistanceGeometry>(
                bakePemDistanceGeometry(tracer, centre, 64, 1000.f, nullptr));
            for (PemSampleMap& s : a.samples)
                s.map.distance = a.distance;
        }
        writePemProbe(a, dir.string(), scene.path());
        manifest = (dir / "manifest.json").string();
    }
    ~PemRoomState() { fs::remove_all(dir); }
};

template <bool Distance> class PemRoomSuite : public ::testing::Test {
protected:
    static constexpr int kWidth = PemRoomState::kWidth, kHeight = PemRoomState::kHeight;

    static void SetUpTestSuite() { room_ = std::make_unique<PemRoomState>(Distance); }
    static void TearDownTestSuite() { room_.reset(); }

    static const PemStore& store() { return *room_->renderer.probes().store<PemStore>(); }

    static inline std::unique_ptr<PemRoomState> room_;
};
using PemRoom = PemRoomSuite<false>;
using PemDistanceRoom = PemRoomSuite<true>;

struct TwinBounds {
    double share; // of the pixels within 2e-3 of the twin, at least
    double mean;  // mean error, below
};

// The twin runs on the shader's own inputs (probe-local position and reflected direction
// read back as float32) with the block the store uploaded, over the same texels: the shader
// filters with texelFetch, so only float rounding may differ.
void expectShaderMatchesTwin(PemRoomState& room, const TwinBounds& bounds) {
    const int kWidth = PemRoomState::kWidth, kHeight = PemRoomState::kHeight;
    const PemStore& store = *room.renderer.probes().store<PemStore>();
    const CameraView cam = room.scene.camera(kWidth, kHeight);
    const Image mask = erodedMask(room.scene.groundTruth(cam, true).mirrorMask);
    for (const PemProbe settings : {PemProbe{0.f, false}, PemProbe{0.5f, false},
                                    PemProbe{0.3f, false}, PemProbe{0.3f, true}}) {
        room.scene.setProbe(room.manifest, settings);
        const Image colour = room.renderer.render(cam, 0);
        const Image pos = room.renderer.render(cam, 1);
        const Image dir = room.renderer.render(cam, 2);
        const PemGpuProbe* synced = store.probe(room.scene.probeEntity());
        ASSERT_NE(synced, nullptr);
        const PemAsset* asset = synced->asset.get();
        const glsl::PemParams* params = &synced->params;
        const PemBlendWeights w =
            pemBlend(pemSampleParameters(*asset), settings.parameter, settings.nearest);
        EXPECT_EQ(params->layerA, 6 * w.a);
        EXPECT_EQ(params->layerB, 6 * w.b);
        EXPECT_EQ(params->wb, w.wb);
        const PemProbeCpu twin(*asset, *params);
        const test::PixelAgreement px = test::agreeByPixel(
            colour, pos, dir, mask, [&](glm::vec3 x, glm::vec3 l) { return twin.radiance(x, l); },
            2e-3);
        ASSERT_GT(px.n, 500) << "the camera must see the reflectors";
        EXPECT_GT(px.colourSum / double(px.n), 0.25) << "the maps (random in [0, 1)) are drawn";
        std::printf("pem (%s) parameter %.2f%s (samples %d/%d, wb %.2f): twin vs GLSL over %ld "
                    "px: %.3f%% within 2e-3, mean %.2e, worst %.2e\n",
                    asset->geometry.c_str(), double(settings.parameter),
                    settings.nearest ? " nearest" : "", w.a, w.b, double(w.wb), px.n,
                    100.0 * px.share(), px.mean(), px.worst);
        EXPECT_GE(px.share(), bounds.share) << settings.parameter;
        EXPECT_LT(px.mean(), bounds.mean) << settings.parameter;
    }
}

} // namespace

TEST_F(PemRoom, ShaderMatchesCpuTwinPerPixelAtSamplesAndBetween) {
    expectShaderMatchesTwin(*room_, {0.995, 5e-4});
    const auto& drawn = room_->renderer.stats().permutations;
    EXPECT_NE(std::find(drawn.begin(), drawn.end(), "pem"), drawn.end());
}

// The distance geometry's shader against its twin. Its search reads the distance cube at the
// nearest texel, and a point within float rounding of a texel boundary can read the
// neighbour on one side and not the other; the search then continues elsewhere and reads
// other map texels (random, so the error is large where it happens). Such pixels must stay
// rare, as in the distance flavour's twin tests; everywhere else only rounding differs.
TEST_F(PemDistanceRoom, ShaderMatchesCpuTwinPerPixelAtSamplesAndBetween) {
    expectShaderMatchesTwin(*room_, {0.99, 5e-3});
    const auto& drawn = room_->renderer.stats().permutations;
    EXPECT_NE(std::find(drawn.begin(), drawn.end(), "pem-distance"), drawn.end());
    EXPECT_EQ(room_->renderer.stats().probeGpuBytes,
              3u * 6 * 16 * 16 * 16 + 6 * 64 * 64 * 4 + sizeof(glsl::PemParams));

    // Agreement must not be that of two box lookups: the baked cube sees the room, and the
    // same map looked up with box geometry draws something else.
    const PemAsset& asset = *store().probe(room_->scene.probeEntity())->asset;
    const long walls =
        std::count_if(asset.distance->distances.begin(), asset.distance->distances.end(),
                      [&](float d) { return d < asset.distance->dInf; });
    EXPECT_GT(walls, long(asset.distance->distances.size()) / 2);
    const CameraView cam = room_->scene.camera(kWidth, kHeight);
    const Image mask = erodedMask(room_->scene.groundTruth(cam, true).mirrorMask);
    room_->scene.setProbe(room_->manifest, PemProbe{0.f, false});
    PemMap box = asset.samples[0].map;
    box.distance = nullptr;
    const test::PixelAgreement px = test::agreeByPixel(
        room_->renderer.render(cam, 0), room_->renderer.render(cam, 1),
        room_->renderer.render(cam, 2), mask,
        [&](glm::vec3 x, glm::vec3 l) { return PemLookupCpu(box).radiance(x, l); }, 2e-3);
    std::printf("pem (distance) vs the same map as a box map: %.1f%% of %ld px within 2e-3\n",
                100.0 * px.share(), px.n);
    EXPECT_LT(px.share(), 0.5);
}

TEST_F(PemRoom, ParameterEditUploadsTheBlockOnly) {
    const CameraView cam = room_->scene.camera(kWidth, kHeight);
    room_->scene.setProbe(room_->manifest, PemProbe{0.2f, false});
    const Image before = room_->renderer.render(cam, 0);
    const std::size_t textures = room_->renderer.stats().textureUploads;
    const std::size_t blocks = room_->renderer.stats().parameterUploads;
    room_->scene.setProbe(room_->manifest, PemProbe{0.7f, false});
    const Image after = room_->renderer.render(cam, 0);
    std::printf("pem parameter edit: %zu texture uploads, %zu block uploads\n",
                room_->renderer.stats().textureUploads - textures,
                room_->renderer.stats().parameterUploads - blocks);
    EXPECT_EQ(room_->renderer.stats().textureUploads, textures);
    EXPECT_EQ(room_->renderer.stats().parameterUploads, blocks + 1);
    EXPECT_EQ(store().probe(room_->scene.probeEntity())->params.layerA, 6);
    EXPECT_GT(compareImages(before, after).rmse, 1e-3) << "the edit reached the shader";
    room_->renderer.render(cam, 0); // nothing edited: nothing uploaded
    EXPECT_EQ(room_->renderer.stats().parameterUploads, blocks + 1);
    EXPECT_EQ(room_->renderer.stats().probeGpuBytes,
              3u * 6 * 16 * 16 * 16 + sizeof(glsl::PemParams));
}
