// Compressed PEM probes on disk (issue 36, `--compress bc6h`): every level of every sample map
// is stored as BC6H blocks and read back exactly (texels and blocks), the HDR content of a map
// keeps the codec's quality floor through the PEM path (levels, stacking, files), the writer
// refuses blocks that do not decode to the texels and writes nothing, and the reader refuses a
// compressed manifest of an older format and a file stored otherwise than the manifest says.
#include "components/reflection_probe/pem/pem_asset.h"
#include "components/reflection_probe/pem/pem_map_levels.h"
#include "components/reflection_probe/pem/writer/pem_compression.h"
#include "components/reflection_probe/pem/writer/pem_probe_writer.h"
#include "engine/core/error.h"
#include "engine/image/ktx2.h"
#include "pem_files_fixture.h"
#include "pem_fixtures.h"
#include "support/hdr_test_image.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

using namespace specula;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// Faces of 8, 4, 2 and 1 texels: the last two levels are partial blocks.
PemAsset mipAsset() {
    return test::randomMipPemAsset(8, 4, 2, 23);
}

class PemCompressedFiles : public test::PemFilesTest {
protected:
    PemCompressedFiles() : PemFilesTest("specula-pem-bc6h") {}
};

} // namespace

TEST_F(PemCompressedFiles, EveryLevelIsStoredAsBc6hAndReadBackExactly) {
    const PemAsset original = mipAsset();
    PemAsset a = original;
    compressPemMaps(a);
    ASSERT_EQ(a.compression, PemCompression::Bc6h);
    for (std::size_t k = 0; k < a.samples.size(); ++k) {
        ASSERT_EQ(a.samples[k].blocks.size(), 4u);
        EXPECT_EQ(a.samples[k].blocks[0].size(), 6u * 4u * 16u); // 2 x 2 blocks a face
        EXPECT_EQ(a.samples[k].blocks[3].size(), 6u * 16u);      // 1^2 pads a block a face
        EXPECT_NE(a.samples[k].map.texels, original.samples[k].map.texels)
            << "random texels cannot survive BC6H exactly";
    }
    writePemProbe(a, dir(), "analytic");
    const json m = json::parse(std::ifstream(manifest()));
    EXPECT_EQ(m["compression"], "bc6h");
    EXPECT_EQ(m["format"]["major"], 3);
    EXPECT_EQ(m["format"]["minor"], 2);
    EXPECT_TRUE(readKtx2(file("sample_00.ktx2")).bc6h);
    EXPECT_TRUE(readKtx2(file("sample_01_mip3.ktx2")).bc6h);
    // 16 bytes a 4x4 block against 12 bytes a texel of float RGB.
    EXPECT_LT(fs::file_size(file("sample_00.ktx2")) * 8, 6u * 64u * 12u);

    const PemAsset b = readPemProbe(manifest());
    EXPECT_EQ(b.compression, PemCompression::Bc6h);
    for (std::size_t k = 0; k < a.samples.size(); ++k) {
        EXPECT_EQ(b.samples[k].map.texels, a.samples[k].map.texels);
        EXPECT_EQ(b.samples[k].blocks, a.samples[k].blocks);
    }
}

TEST_F(PemCompressedFiles, AnHdrMapKeepsTheCodecsQualityFloor) {
    PemAsset a;
    a.faceRes = 32;
    a = test::randomPemAsset(a, 1, 5);
    const Image hdr = test::hdrTestImage(32, 6 * 32); // faces stacked, as a level is
    pemUnstackLevel(hdr, 0, a.samples[0].map);
    compressPemMaps(a);
    writePemProbe(a, dir(), "analytic");
    const Image back = pemStackLevel(readPemProbe(manifest()).samples[0].map, 0);
    const double logPsnr = test::logLuminancePsnr(hdr, back), lin = test::linearPsnr(hdr, back);
    std::printf("[pem-bc6h] 32^2 x 6 HDR map: log-luminance PSNR %.2f dB, linear %.2f dB\n",
                logPsnr, lin);
    // The codec's own floor (image/bc6h_test) on the same content: a face stacked out of
    // order or a level's blocks swapped costs tens of dB.
    EXPECT_GE(logPsnr, 48.0);
    EXPECT_GE(lin, 45.0);
}

TEST_F(PemCompressedFiles, TheWriterRefusesBlocksThatDoNotHoldTheMapAndWritesNothing) {
    PemAsset a = mipAsset();
    compressPemMaps(a);
    a.samples[1].map.texels[PemMap::levelOffset(8, 2)].x += 0.25f; // level 2, after the blocks
    try {
        writePemProbe(a, dir(), "analytic");
        ADD_FAILURE() << "expected the writer to refuse";
    } catch (const Error& e) {
        std::printf("refused: %s\n", e.what());
        EXPECT_TRUE(e.file().ends_with("sample_01.ktx2")) << e.what();
        EXPECT_EQ(e.field(), "radiance");
        EXPECT_NE(std::string(e.what()).find("level 2"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(dir()));
    a = mipAsset();
    compressPemMaps(a);
    a.samples[0].blocks.pop_back();
    EXPECT_THROW(writePemProbe(a, dir(), "analytic"), Error);
    EXPECT_FALSE(fs::exists(dir()));
}

TEST_F(PemCompressedFiles, TheReaderRefusesCompressionItCannotTrust) {
    PemAsset a = mipAsset();
    compressPemMaps(a);
    writePemProbe(a, dir(), "analytic");
    editManifest([](json& m) {
        m.erase("seal");
        m["format"]["minor"] = 1;
    });
    expectRefused("manifest.json", "compression"); // 3.1 knew no compressed PEM
    editManifest([](json& m) { m["compression"] = "bc7"; });
    expectRefused("manifest.json", "compression");

    fs::remove_all(dir());
    writePemProbe(mipAsset(), dir(), "analytic"); // float maps
    editManifest([](json& m) {
        m.erase("seal");
        m["format"] = {{"name", "specula-probe"}, {"major", 3}, {"minor", 2}};
        m["compression"] = "bc6h";
    });
    expectRefused("sample_00.ktx2", "vkFormat");
    editManifest([](json& m) { m.erase("compression"); });
    EXPECT_NO_THROW(readPemProbe(manifest())); // float maps in a 3.2 manifest read as ever

    fs::remove_all(dir());
    writePemProbe(a, dir(), "analytic"); // BC6H maps ...
    editManifest([](json& m) {
        m.erase("seal");
        m.erase("compression"); // ... in a manifest that states none
    });
    expectRefused("sample_00.ktx2", "vkFormat");
}
