// MIP levels on disk (issue 12): a multi-level asset round-trips level by level, the reader
// names the manifest and the field when a level's file is missing or mis-sized, and a
// single-level asset is written and read exactly as before ("mip_levels" and "mips" absent).
#include "components/reflection_probe/pem/pem_asset.h"
#include "components/reflection_probe/pem/writer/pem_probe_writer.h"
#include "engine/core/error.h"
#include "engine/image/ktx2.h"
#include "engine/image_io/image_io.h"
#include "pem_files_fixture.h"
#include "pem_fixtures.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

using namespace specula;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// Faces of 6, 3 and 1 texels: odd sizes halve as GL's levels do.
PemAsset mipAsset(int levels) {
    return test::randomMipPemAsset(6, levels, 2, 17);
}

class PemMipFiles : public test::PemFilesTest {
protected:
    PemMipFiles() : PemFilesTest("specula-pem-mip") {}
};

} // namespace

TEST_F(PemMipFiles, EveryLevelRoundTrips) {
    const PemAsset a = mipAsset(3);
    writePemProbe(a, dir(), "analytic");
    const json m = json::parse(std::ifstream(manifest()));
    EXPECT_EQ(m["mip_levels"], 3);
    ASSERT_EQ(m["samples"][1]["mips"].size(), 2u);
    EXPECT_EQ(m["samples"][1]["mips"][0]["file"], "sample_01_mip1.ktx2");
    const PemAsset b = readPemProbe(manifest());
    EXPECT_EQ(b.mipLevels, 3);
    for (std::size_t k = 0; k < 2; ++k) {
        EXPECT_EQ(b.samples[k].map.levels, 3);
        EXPECT_EQ(b.samples[k].map.texels, a.samples[k].map.texels);
    }
    const Image level1 = readKtx2(file("sample_00_mip1.ktx2")).levels[0];
    EXPECT_EQ(level1.width, 3);
    EXPECT_EQ(level1.height, 18);
    const Image level2 = readKtx2(file("sample_01_mip2.ktx2")).levels[0];
    EXPECT_EQ(level2.width, 1);
    EXPECT_EQ(level2.height, 6);
}

TEST_F(PemMipFiles, SingleLevelAssetsAreWrittenAsBefore) {
    writePemProbe(mipAsset(1), dir(), "analytic");
    const json m = json::parse(std::ifstream(manifest()));
    EXPECT_FALSE(m.contains("mip_levels"));
    EXPECT_FALSE(m["samples"][0].contains("mips"));
    EXPECT_FALSE(fs::exists(file("sample_00_mip1.ktx2")));
    const PemAsset b = readPemProbe(manifest());
    EXPECT_EQ(b.mipLevels, 1);
    EXPECT_EQ(b.samples[0].map.levels, 1);
    EXPECT_EQ(b.samples[0].map.texels.size(), std::size_t(PemMap::texelCount(6)));
}

TEST_F(PemMipFiles, ReaderRefusesAMissingOrMisSizedLevelNamingFileAndField) {
    const PemAsset a = mipAsset(3);
    auto rewrite = [&] {
        fs::remove_all(dir());
        writePemProbe(a, dir(), "analytic");
    };
    rewrite();
    fs::remove(file("sample_01_mip2.ktx2"));
    expectRefused("manifest.json", "samples[1].mips[1].file");

    rewrite(); // a level of the wrong size under a matching checksum
    writeKtx2Cube(file("sample_00_mip1.ktx2"), Image(2, 12, 3));
    editManifest([&](json& m) {
        m["samples"][0]["mips"][0]["checksum"] = fileChecksum(file("sample_00_mip1.ktx2"));
    });
    expectRefused("manifest.json", "samples[0].mips[0].file");

    rewrite(); // a level left out of the list
    editManifest([](json& m) { m["samples"][1]["mips"].erase(1); });
    expectRefused("manifest.json", "samples[1].mips");

    rewrite();
    editManifest([](json& m) { m["samples"][0].erase("mips"); });
    expectRefused("manifest.json", "samples[0].mips");

    rewrite(); // faces of 6 have three levels
    editManifest([](json& m) { m["mip_levels"] = 4; });
    expectRefused("manifest.json", "mip_levels");

    rewrite(); // a level's radiance out of range names its file's level
    Image img = readKtx2(file("sample_00_mip2.ktx2")).levels[0];
    img.at(0, 4)[1] = -1.f;
    writeKtx2Cube(file("sample_00_mip2.ktx2"), img);
    editManifest([&](json& m) {
        m["samples"][0]["mips"][1]["checksum"] = fileChecksum(file("sample_00_mip2.ktx2"));
    });
    expectRefused("sample_00.ktx2 (level 2)", "radiance");
}

TEST_F(PemMipFiles, WriterRefusesMapsUnlikeTheAssetsLevels) {
    PemAsset a = mipAsset(3);
    a.samples[1].map.texels.pop_back();
    EXPECT_THROW(writePemProbe(a, dir(), "analytic"), Error);
    EXPECT_FALSE(fs::exists(dir()));
    a = mipAsset(3);
    a.samples[0].map.levels = 2;
    try {
        writePemProbe(a, dir(), "analytic");
        ADD_FAILURE() << "a map of 2 levels in a 3-level asset was written";
    } catch (const Error& e) {
        EXPECT_EQ(e.field(), "samples[0].map") << e.what();
    }
    EXPECT_FALSE(fs::exists(dir()));
}
