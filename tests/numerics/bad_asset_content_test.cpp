// Cooked distance probes whose checksums are valid but whose content is not (issue 10): the
// reader checks every texel, each layer's figures against its image and the composite against
// the object layers, opens only regular files, and names the file and the field. Every
// tampered probe is made here from a small valid one.
#include "bad_input_support.h"

#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "components/reflection_probe/distance/writer/distance_probe_writer.h"
#include "engine/image/ktx2.h"
#include "engine/image_io/image_io.h"
#include "probe/analytic_probe.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <limits>
#include <sys/stat.h>

namespace fs = std::filesystem;
using nlohmann::json;
using namespace specula;
using namespace specula::test;

namespace {

constexpr int kRes = 16;
const glm::vec3 kBallCentre{1.5f, 0.f, 0.f};
constexpr float kBallRadius = 0.5f;

// Distance from the origin along unit d to the ball, or +inf.
float ballHit(glm::vec3 d) {
    const float b = glm::dot(d, kBallCentre);
    const float disc = b * b - (glm::dot(kBallCentre, kBallCentre) - kBallRadius * kBallRadius);
    const float t = b - std::sqrt(std::max(disc, 0.f));
    return disc >= 0.f && t > 0.f ? t : std::numeric_limits<float>::infinity();
}

// A three-layer probe: the composite (box room with a ball in it), then the ball, then the
// room, each with the figures a bake would store.
DistanceProbeAsset ballInBox() {
    const AnalyticBox box;
    DistanceProbeAsset a = makeBoxProbe(box, kRes);
    auto surface = [&](bool withBall, bool withBox) {
        return [=](glm::vec3 d) {
            const float tb = withBall ? ballHit(d) : std::numeric_limits<float>::infinity();
            const float tw = withBox ? box.exit(glm::vec3(0.f), d) : tb;
            const float t = std::min(tb, tw);
            return std::pair(t, t == tb ? glm::vec3(0.9f, 0.2f, 0.1f)
                                        : AnalyticBox::radianceAt(t * d));
        };
    };
    a.layers = {bakeAnalyticLayer("composite", kRes, a.dInf, surface(true, true)),
                bakeAnalyticLayer("ball", kRes, a.dInf, surface(true, false)),
                bakeAnalyticLayer("room", kRes, a.dInf, surface(false, true))};
    for (DistanceProbeLayer& L : a.layers) {
        const DistanceLayerContent c = measureDistanceLayer(L.faces, a.dInf, L.name);
        L.solidAngle = float(c.solidAngle);
        L.avgDistance = 0.5f * (c.minDistance + c.maxDistance);
        L.method = "bisection";
    }
    return a;
}

class BadAssetContent : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("specula-bad-content-" + std::to_string(::getpid()) + "-" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        writeDistanceProbe(ballInBox(), probe().string(), "analytic");
        good_ = json::parse(slurp(manifest()));
    }
    void TearDown() override { fs::remove_all(dir_); }

    fs::path probe() const { return dir_ / "probe"; }
    fs::path manifest() const { return probe() / "manifest.json"; }
    fs::path layer(int i) const {
        return probe() / good_["layers"][std::size_t(i)]["file"].get<std::string>();
    }
    void writeManifest(const json& m) const { spit(manifest(), m.dump(2)); }
    std::string readError() const {
        return errorOf([&] { readDistanceProbe(manifest().string()); });
    }

    // Rewrites layer i's image through `edit` and stores its new checksum: only the content
    // is wrong, as a corrupted-then-recooked or hand-edited file would be.
    void tamperLayer(int i, const std::function<void(Image&)>& edit) {
        Image img = readKtx2(layer(i).string()).levels[0];
        edit(img);
        writeKtx2Cube(layer(i).string(), img);
        json m = good_;
        m["layers"][std::size_t(i)]["checksum"] = fileChecksum(layer(i).string());
        writeManifest(m);
    }
    // Replaces layer i's file by something else (a FIFO, a link...), checksum untouched.
    template <typename Make> void replaceLayerFile(int i, Make make) {
        fs::remove(layer(i));
        make(layer(i));
    }

    fs::path dir_;
    json good_;
};

TEST_F(BadAssetContent, GoodProbeReadsWithItsFigures) {
    const DistanceProbeAsset a = readDistanceProbe(manifest().string());
    ASSERT_EQ(a.layers.size(), 3u);
    // Independent truths: the room surrounds the probe (4 pi sr); the ball of radius r at
    // distance c subtends 2 pi (1 - cos asin(r / c)) sr, to within the 16x16 texels' edges.
    EXPECT_NEAR(a.layers[2].solidAngle, 4.0 * M_PI, 1e-4);
    const double cap = 2.0 * M_PI * (1.0 - std::cos(std::asin(kBallRadius / 1.5)));
    EXPECT_NEAR(a.layers[1].solidAngle, cap, 0.35 * cap);
    EXPECT_NEAR(a.layers[1].minDistance, 1.0f, 0.02f); // the ball's near pole
    // The composite's farthest hit is the room's; the room layer is stored as half floats
    // (11 significant bits: within 2^-11 of it).
    EXPECT_NEAR(a.layers[0].maxDistance, a.layers[2].maxDistance,
                a.layers[0].maxDistance * std::ldexp(1.0, -11));
}

TEST_F(BadAssetContent, SolidAngleOfACubeFaceIsTheSixthOfTheSphere) {
    for (int n : {1, 3, 64}) {
        double sum = 0.0;
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                sum += cubeTexelSolidAngle(x, y, n);
        EXPECT_NEAR(sum, 4.0 * M_PI / 6.0, 1e-12) << n;
    }
}

TEST_F(BadAssetContent, AllNanCompositeIsRefused) {
    tamperLayer(0, [](Image& img) {
        for (float& v : img.pixels)
            v = std::numeric_limits<float>::quiet_NaN();
    });
    expectNames(readError(), {"layer_00.ktx2", "radiance", "nan"});
}

TEST_F(BadAssetContent, RadianceBeyondHalfFloatIsRefused) {
    tamperLayer(1, [](Image& img) { img.at(3, 2)[1] = 1e38f; });
    expectNames(readError(), {"layer_01.ktx2", "radiance", "1e+38", "texel (3, 2)", "channel G"});
    tamperLayer(1, [](Image& img) { img.at(3, 2)[1] = -0.5f; });
    expectNames(readError(), {"layer_01.ktx2", "radiance", "-0.5"});
}

TEST_F(BadAssetContent, DistancesOutsideZeroToDInfAreRefused) {
    const float bad[] = {0.f, -1.f, std::numeric_limits<float>::infinity(),
                         std::numeric_limits<float>::quiet_NaN(), 1000.5f};
    for (const float d : bad) {
        tamperLayer(2, [&](Image& img) { img.at(5, 7 * kRes / 2)[3] = d; });
        expectNames(readError(), {"layer_02.ktx2", "distance", "face -Y texel (5, 8)"});
    }
}

TEST_F(BadAssetContent, PngRenamedKtx2IsRefused) {
    Image img = readKtx2(layer(1).string()).levels[0];
    writeImage((dir_ / "fake.png").string(), img);
    fs::rename(dir_ / "fake.png", layer(1));
    json m = good_;
    m["layers"][1]["checksum"] = fileChecksum(layer(1).string());
    writeManifest(m);
    expectNames(readError(), {"layer_01.ktx2", "identifier", "not a KTX 2.0 file"});
}

TEST_F(BadAssetContent, ManifestNumbersAreRangeChecked) {
    auto refused = [&](const std::function<void(json&)>& edit,
                       std::initializer_list<std::string> parts) {
        json m = good_;
        edit(m);
        writeManifest(m);
        expectNames(readError(), parts);
    };
    refused([](json& m) { m["centre"] = {1e308, 0, 0}; }, {"manifest.json", "centre"});
    refused([](json& m) { m["centre"] = {0, -2e7, 0}; }, {"manifest.json", "centre"});
    refused([](json& m) { m["face_res"] = kRes + 0.5; }, {"manifest.json", "face_res", "integer"});
    refused([](json& m) { m["box"]["max"] = {1e300, 0, 0}; }, {"manifest.json", "box.max"});
    refused(
        [](json& m) {
            m["layers"][1]["objects"] = {"ball", 7};
        },
        {"manifest.json", "layers[1].objects"});
    // A JSON number no double holds: nlohmann alone says "number overflow" naming neither.
    spit(manifest(), withRawValue(good_, "d_inf", "1e999"));
    expectNames(readError(), {"manifest.json: d_inf: number out of range"});
}

TEST_F(BadAssetContent, LayersSwappedWithTheirChecksumsAreRefused) {
    // The files of two object layers trade places, their checksums with them.
    json m = good_;
    std::swap(m["layers"][1]["file"], m["layers"][2]["file"]);
    std::swap(m["layers"][1]["checksum"], m["layers"][2]["checksum"]);
    writeManifest(m);
    expectNames(readError(), {"manifest.json", "layers[1].", "swapped"});
    // Whole entries, figures included, trade places with the composite: only the per-texel
    // check that layer 0 is the nearest can tell.
    m = good_;
    std::swap(m["layers"][0], m["layers"][1]);
    writeManifest(m);
    expectNames(readError(), {"manifest.json", "layers[0]", "nearest"});
}

TEST_F(BadAssetContent, EditedFiguresAreRefused) {
    json m = good_;
    m["layers"][2]["max_distance"] = m["layers"][2]["max_distance"].get<double>() * 0.9;
    writeManifest(m);
    expectNames(readError(), {"manifest.json", "layers[2].max_distance"});
    m = good_;
    m["layers"][1]["solid_angle_sr"] = 2.0;
    writeManifest(m);
    expectNames(readError(), {"manifest.json", "layers[1].solid_angle_sr"});
}

TEST_F(BadAssetContent, LayerFileThatIsAFifoIsRefusedWithoutBlocking) {
    // Layer 0: the child meets it before any image is decoded (see errorOfInChild).
    replaceLayerFile(0, [](const fs::path& p) { ASSERT_EQ(::mkfifo(p.c_str(), 0600), 0); });
    expectNames(errorOfInChild([&] { readDistanceProbe(manifest().string()); }),
                {"manifest.json", "layers[0].file", "layer_00.ktx2", "FIFO"});
}

TEST_F(BadAssetContent, LayerFileLinkedToDevZeroIsRefusedWithoutSpinning) {
    replaceLayerFile(0, [](const fs::path& p) { fs::create_symlink("/dev/zero", p); });
    expectNames(errorOfInChild([&] { readDistanceProbe(manifest().string()); }),
                {"manifest.json", "layers[0].file", "character device"});
}

TEST_F(BadAssetContent, LayerFileThatIsADirectoryIsNamedAsOne) {
    replaceLayerFile(2, [](const fs::path& p) { fs::create_directory(p); });
    const std::string what = readError();
    expectNames(what, {"manifest.json", "layers[2].file", "a directory"});
    EXPECT_EQ(what.find("checksum"), std::string::npos) << what;
}

TEST_F(BadAssetContent, SymlinkLoopIsNamed) {
    replaceLayerFile(0, [](const fs::path& p) {
        fs::create_symlink(p.filename().string() + ".b", p);
        fs::create_symlink(p.filename(), p.string() + ".b");
    });
    expectNames(readError(), {"manifest.json", "layers[0].file", "symlink loop"});
}

TEST_F(BadAssetContent, ManifestThatIsAFifoIsRefusedWithoutBlocking) {
    fs::remove(manifest());
    ASSERT_EQ(::mkfifo(manifest().c_str(), 0600), 0);
    expectNames(errorOfInChild([&] { readDistanceProbe(manifest().string()); }),
                {"manifest.json", "FIFO"});
}

TEST_F(BadAssetContent, WriterRefusesWhatTheReaderWould) {
    DistanceProbeAsset a = ballInBox();
    a.layers[1].faces[2].at(1, 1)[3] = -3.f;
    const fs::path out = dir_ / "never";
    expectNames(errorOf([&] { writeDistanceProbe(a, out.string(), "analytic"); }),
                {"layer_01.ktx2", "distance", "-3"});
    EXPECT_FALSE(fs::exists(out));
    a = ballInBox();
    a.centre = glm::vec3(3e7f, 0.f, 0.f);
    expectNames(errorOf([&] { writeDistanceProbe(a, out.string(), "analytic"); }), {"centre"});
    a = ballInBox();
    std::swap(a.layers[0], a.layers[2]);
    expectNames(errorOf([&] { writeDistanceProbe(a, out.string(), "analytic"); }),
                {"layers[0]", "nearest"});
    EXPECT_FALSE(fs::exists(out));
}

} // namespace
