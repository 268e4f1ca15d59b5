// The local layer on disk (issue 12): a layered asset round-trips, and the reader refuses a
// local-layer EXR that is missing, of the wrong size or without alpha, naming the file and the
// field, while a manifest without "local_layer" reads as a single-map asset.
#include "components/reflection_probe/pem/pem_asset.h"
#include "components/reflection_probe/pem/writer/pem_probe_writer.h"
#include "engine/core/error.h"
#include "engine/image/ktx2.h"
#include "engine/image_io/image_io.h"
#include "pem_files_fixture.h"
#include "pem_fixtures.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace specula;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

PemAsset layeredAsset(int faceRes, int localRes, int count) {
    PemAsset a;
    a.centre = {0.f, 1.f, 0.f};
    a.faceRes = faceRes;
    a.localLayer = true;
    a.localFaceRes = localRes;
    a.localSphere = {{0.1f, -0.05f, 0.f}, 0.45f};
    return test::randomPemAsset(a, count, 5);
}

class PemLocalFiles : public test::PemFilesTest {
protected:
    PemLocalFiles() : PemFilesTest("specula-pem-local") {}

    std::string localFile(int k) const { return file("local_0" + std::to_string(k) + ".ktx2"); }
};

} // namespace

TEST_F(PemLocalFiles, LayeredAssetRoundTrips) {
    const PemAsset a = layeredAsset(4, 3, 2);
    writePemProbe(a, dir(), "analytic");
    const PemAsset b = readPemProbe(manifest());
    EXPECT_TRUE(b.localLayer);
    EXPECT_EQ(b.localFaceRes, 3);
    EXPECT_EQ(b.localSphere, a.localSphere);
    for (std::size_t k = 0; k < 2; ++k) {
        const PemMap& m = b.samples[k].local;
        EXPECT_EQ(m.faceRes, 3);
        EXPECT_EQ(m.local, a.localSphere);
        EXPECT_EQ(m.texels, a.samples[k].local.texels);
        EXPECT_EQ(m.alpha, a.samples[k].local.alpha);
        EXPECT_EQ(b.samples[k].localFile, "local_0" + std::to_string(k) + ".ktx2");
        EXPECT_EQ(b.samples[k].localChecksum, fileChecksum(localFile(int(k))));
        EXPECT_EQ(b.samples[k].map.texels, a.samples[k].map.texels);
    }
    const Image img = readKtx2(localFile(1)).levels[0];
    EXPECT_EQ(img.width, 3);
    EXPECT_EQ(img.height, 18);
    EXPECT_EQ(img.channels, 4);
}

TEST_F(PemLocalFiles, ManifestWithoutLocalLayerReadsAsSingleMap) {
    PemAsset a = layeredAsset(4, 3, 2);
    a.localLayer = false;
    for (PemSampleMap& s : a.samples)
        s.local = PemMap{};
    writePemProbe(a, dir(), "analytic");
    const json m = json::parse(std::ifstream(manifest()));
    EXPECT_FALSE(m.contains("local_layer"));
    EXPECT_FALSE(m["samples"][0].contains("local"));
    EXPECT_FALSE(fs::exists(localFile(0)));
    const PemAsset b = readPemProbe(manifest());
    EXPECT_FALSE(b.localLayer);
    EXPECT_EQ(b.samples[0].local.faceRes, 0);
}

TEST_F(PemLocalFiles, ReaderRefusesABadLocalLayerNamingFileAndField) {
    const PemAsset a = layeredAsset(4, 3, 2);
    auto rewrite = [&] {
        fs::remove_all(dir());
        writePemProbe(a, dir(), "analytic");
    };
    rewrite();
    fs::remove(localFile(1));
    expectRefused("manifest.json", "samples[1].local.file");

    rewrite(); // the layer's size says 5, the images are 3 x 18
    editManifest([](json& m) { m["local_layer"]["face_res"] = 5; });
    expectRefused("manifest.json", "samples[0].local.file");

    rewrite(); // an image of the wrong size under a matching checksum
    writeKtx2Cube(localFile(0), Image(4, 24, 4));
    editManifest(
        [&](json& m) { m["samples"][0]["local"]["checksum"] = fileChecksum(localFile(0)); });
    expectRefused("manifest.json", "samples[0].local.file");

    rewrite(); // RGB only: no coverage
    writeKtx2Cube(localFile(1), Image(3, 18, 3));
    editManifest(
        [&](json& m) { m["samples"][1]["local"]["checksum"] = fileChecksum(localFile(1)); });
    expectRefused("local_01.ktx2", "channels");

    rewrite(); // a coverage past 1
    Image img = readKtx2(localFile(0)).levels[0];
    img.at(1, 7)[3] = 1.5f;
    writeKtx2Cube(localFile(0), img);
    editManifest(
        [&](json& m) { m["samples"][0]["local"]["checksum"] = fileChecksum(localFile(0)); });
    expectRefused("local_00.ktx2", "alpha");

    rewrite();
    editManifest([](json& m) { m["samples"][1].erase("local"); });
    expectRefused("manifest.json", "samples[1].local");

    rewrite();
    editManifest([](json& m) { m["local_layer"]["radius"] = -1.0; });
    expectRefused("manifest.json", "local_layer.radius");
}

TEST_F(PemLocalFiles, WriterRefusesWhatTheReaderWould) {
    PemAsset a = layeredAsset(4, 3, 2);
    a.samples[1].local.alpha[4] = -0.25f;
    try {
        writePemProbe(a, dir(), "analytic");
        ADD_FAILURE() << "expected alpha to be refused";
    } catch (const Error& e) {
        EXPECT_TRUE(e.file().ends_with("local_01.ktx2")) << e.what();
        EXPECT_EQ(e.field(), "alpha") << e.what();
    }
    a.samples[1].local.alpha[4] = 0.25f;
    a.samples[0].local.faceRes = 2;
    try {
        writePemProbe(a, dir(), "analytic");
        ADD_FAILURE() << "expected samples[0].local to be refused";
    } catch (const Error& e) {
        EXPECT_EQ(e.field(), "samples[0].local") << e.what();
    }
    EXPECT_FALSE(fs::exists(dir())) << "nothing is written on failure";
}
