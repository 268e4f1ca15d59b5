// The runtime side of the parameterized-environment-map flavour: the asset's write/read
// round trip and what the reader refuses, the blend weights, the shader against its CPU twin
// on the default room (at a sample and between two), and a parameter edit that uploads the
// parameter block only. Components, engine and cooker only: no sandbox code.
#include "components/reflection_probe/pem/pem_asset.h"
#include "components/reflection_probe/pem/pem_blend.h"
#include "components/reflection_probe/pem/pem_probe_cpu.h"
#include "components/reflection_probe/pem/pem_store.h"
#include "engine/core/error.h"
#include "engine/gpu/context.h"
#include "engine/image/compare.h"
#include "engine/image/image_io.h"
#include "engine/scene/mesh_bounds.h"
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
namespace fs = std::filesystem;

namespace {

// `count` samples at parameters 0 .. 1, evenly spaced, each map random in [0, 1).
PemAsset randomAsset(int faceRes, int count, glm::vec3 boxMin, glm::vec3 boxMax,
                     unsigned seed = 7) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    PemAsset a;
    a.centre = {0.25f, 1.5f, -0.5f};
    a.parameterKind = "reflector";
    a.path = "line";
    a.faceRes = faceRes;
    a.boxMin = boxMin;
    a.boxMax = boxMax;
    for (int k = 0; k < count; ++k) {
        PemSampleMap s;
        s.parameter = count > 1 ? float(k) / float(count - 1) : 0.f;
        s.map = {faceRes, boxMin, boxMax, {}};
        for (int t = 0; t < PemMap::texelCount(faceRes); ++t)
            s.map.texels.emplace_back(u(rng), u(rng), u(rng));
        a.samples.push_back(std::move(s));
    }
    return a;
}

class PemAssetFiles : public test::ScratchDirTest {
protected:
    PemAssetFiles() : ScratchDirTest("specula-pem-asset") {}

    std::string dir() const { return (root_ / "pem").string(); }
    std::string manifest() const { return dir() + "/manifest.json"; }
    std::string sampleFile(int k) const { return dir() + "/sample_0" + std::to_string(k) + ".exr"; }

    // Rewrites the written manifest through `edit`.
    void editManifest(const std::function<void(json&)>& edit) const {
        json m = json::parse(std::ifstream(manifest()));
        edit(m);
        std::ofstream(manifest()) << m.dump(1);
    }
    // Reading must fail naming `file` (a suffix of it) and `field`.
    void expectRefused(const std::string& fileSuffix, const std::string& field) const {
        try {
            readPemProbe(manifest());
            ADD_FAILURE() << "expected " << field << " to be refused";
        } catch (const Error& e) {
            std::printf("refused: %s\n", e.what());
            EXPECT_TRUE(e.file().ends_with(fileSuffix)) << e.what();
            EXPECT_EQ(e.field(), field) << e.what();
        }
    }
};

} // namespace

TEST_F(PemAssetFiles, RoundTripKeepsEveryFieldAndTexel) {
    const PemAsset a = randomAsset(4, 3, glm::vec3(-2.f, -1.f, -3.f), glm::vec3(2.f, 3.f, 1.f));
    writePemProbe(a, dir(), "analytic");
    const PemAsset b = readPemProbe(manifest());
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
        EXPECT_EQ(b.samples[k].file, "sample_0" + std::to_string(k) + ".exr");
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
    refused("sample_01.exr", "radiance");
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
    Image img = readFloatExr(sampleFile(2));
    img.at(3, 9)[1] = NAN;
    writeImage(sampleFile(2), img);
    editManifest([&](json& m) { m["samples"][2]["checksum"] = fileChecksum(sampleFile(2)); });
    expectRefused("sample_02.exr", "radiance");

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
// reflectors, a headless context and a renderer (built-in flavours: PEM included).
// Everything a PemRoom test draws with, made once per suite; members are destroyed in
// reverse, so the GL objects go before the context.
struct PemRoomState {
    static constexpr int kWidth = 200, kHeight = 150;

    std::unique_ptr<gpu::GlContext> context = gpu::GlContext::createHeadless();
    test::ProbeRoom scene{test::kRoomScene, test::kRoomSky};
    test::RoomRenderer renderer{scene, kWidth, kHeight};
    std::string manifest;
    fs::path dir = fs::temp_directory_path() / ("specula-pem-room-" + std::to_string(::getpid()));

    PemRoomState() {
        const glm::vec3 centre = scene.probeCentre();
        Aabb box;
        for (const ReflectorMarkup& r : scene.markup().reflectors)
            for (ecs::Entity mesh : r.meshes)
                box.extend(meshWorldBoundsConservative(scene.registry(), mesh));
        PemAsset a = randomAsset(16, 3, box.min - centre - 0.5f, box.max - centre + 0.5f);
        a.centre = centre;
        writePemProbe(a, dir.string(), scene.path());
        manifest = (dir / "manifest.json").string();
    }
    ~PemRoomState() { fs::remove_all(dir); }
};

class PemRoom : public ::testing::Test {
protected:
    static constexpr int kWidth = PemRoomState::kWidth, kHeight = PemRoomState::kHeight;

    static void SetUpTestSuite() { room_ = std::make_unique<PemRoomState>(); }
    static void TearDownTestSuite() { room_.reset(); }

    static const PemStore& store() { return *room_->renderer.probes().store<PemStore>(); }

    static inline std::unique_ptr<PemRoomState> room_;
};

} // namespace

TEST_F(PemRoom, ShaderMatchesCpuTwinPerPixelAtSamplesAndBetween) {
    // The twin runs on the shader's own inputs (probe-local position and reflected direction
    // read back as float32) with the block the store uploaded, over the same texels: the
    // shader filters with texelFetch, so only float rounding may differ.
    const CameraView cam = room_->scene.camera(kWidth, kHeight);
    const Image mask = erodedMask(room_->scene.groundTruth(cam, true).mirrorMask);
    for (const PemProbe settings : {PemProbe{0.f, false}, PemProbe{0.5f, false},
                                    PemProbe{0.3f, false}, PemProbe{0.3f, true}}) {
        room_->scene.setProbe(room_->manifest, settings);
        const Image colour = room_->renderer.render(cam, 0);
        const Image pos = room_->renderer.render(cam, 1);
        const Image dir = room_->renderer.render(cam, 2);
        const PemProbeGpu* synced = store().probe(room_->scene.probeEntity());
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
        std::printf("pem parameter %.2f%s (samples %d/%d, wb %.2f): twin vs GLSL over %ld px: "
                    "%.3f%% within 2e-3, mean %.2e, worst %.2e\n",
                    double(settings.parameter), settings.nearest ? " nearest" : "", w.a, w.b,
                    double(w.wb), px.n, 100.0 * px.share(), px.mean(), px.worst);
        EXPECT_GE(px.share(), 0.995) << settings.parameter;
        EXPECT_LT(px.mean(), 5e-4) << settings.parameter;
    }
    const auto& drawn = room_->renderer.stats().permutations;
    EXPECT_NE(std::find(drawn.begin(), drawn.end(), "pem"), drawn.end());
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
