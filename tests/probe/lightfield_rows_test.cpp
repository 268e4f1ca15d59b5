// A light-field probe baked in blocks (lightfield_rows.h): each slab's camera rows traced
// apart and assembled, in any order and any split, give the same asset, byte for byte, as
// bakeLightFieldProbe; blocks that miss or overlap rows are refused naming them; the block
// file round-trips and refuses a wrong header, a wrong shape and a truncated or overlong file.
#include "assetcooker/lib/flavours/lightfield/lightfield_bake.h"
#include "assetcooker/lib/scene/probe_setup.h"
#include "engine/core/error.h"
#include "support/scratch_dir_test.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace specula {
namespace {

namespace fs = std::filesystem;

const std::string kScene = SPECULA_SOURCE_DIR "/assets/two_rooms/two_rooms.gltf";
const std::string kSky = SPECULA_SOURCE_DIR "/assets/scenes/env/field.jpg";

bool sameBits(float a, float b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

void expectSameAsset(const LightFieldAsset& a, const LightFieldAsset& b) {
    for (int k = 0; k < 6; ++k) {
        const LightFieldSlab &x = a.slabs[std::size_t(k)], &y = b.slabs[std::size_t(k)];
        EXPECT_TRUE(x.data == y.data) << "slab " << k << " bytes differ";
        for (const auto& [p, q] : {std::pair{x.nearDepth, y.nearDepth},
                                   {x.farDepth, y.farDepth},
                                   {x.minDepth, y.minDepth},
                                   {x.maxDepth, y.maxDepth},
                                   {x.skyFraction, y.skyFraction},
                                   {x.intrudingFraction, y.intrudingFraction},
                                   {x.focalDepth, y.focalDepth},
                                   {x.disparity, y.disparity}})
            EXPECT_TRUE(sameBits(p, q)) << "slab " << k << ": " << p << " vs " << q;
    }
    EXPECT_EQ(a.intrusions.size(), b.intrusions.size());
}

class LightFieldRowsTest : public test::ScratchDirTest {
protected:
    LightFieldRowsTest() : ScratchDirTest("specula-lf-rows") {}

    static void SetUpTestSuite() { scene_ = new ProbeScene(kScene, kSky); }
    static void TearDownTestSuite() { delete scene_; }

    static LightFieldBakeOptions options(LightFieldCompression c = LightFieldCompression::None) {
        LightFieldBakeOptions o;
        o.cellCentre = markupProbeCentre(scene_->registry, scene_->markup, scene_->loaded);
        o.cellSize = markupCellSize(scene_->markup);
        o.cameras = 3;
        o.res = 8;
        o.compression = c;
        o.sky = &scene_->sky;
        return o;
    }

    // Every slab's rows in blocks of `rows` (the last shorter).
    static std::vector<LightFieldRows> blocks(const LightFieldBakeOptions& o, int rows) {
        std::vector<LightFieldRows> out;
        for (int s = 0; s < 6; ++s)
            for (int j = 0; j < o.cameras; j += rows)
                out.push_back(traceLightFieldRows(scene_->registry, scene_->markup, o, s, j,
                                                  std::min(o.cameras, j + rows)));
        return out;
    }

    static LightFieldAsset assemble(LightFieldBakeOptions o, const std::vector<LightFieldRows>& b) {
        o.blocks = &b;
        return bakeLightFieldProbe(scene_->registry, scene_->markup, o);
    }

    static inline ProbeScene* scene_ = nullptr;
};

TEST_F(LightFieldRowsTest, BlocksInAnyOrderAndSplitAssembleToTheWholeBakeByteForByte) {
    for (const LightFieldCompression c :
         {LightFieldCompression::None, LightFieldCompression::BC1}) {
        const LightFieldBakeOptions o = options(c);
        const LightFieldAsset whole = bakeLightFieldProbe(scene_->registry, scene_->markup, o);
        std::mt19937 random(7);
        for (const int rows : {1, 2, 3}) {
            std::vector<LightFieldRows> b = blocks(o, rows);
            EXPECT_EQ(b.size(), std::size_t(6 * ((3 + rows - 1) / rows)));
            expectSameAsset(assemble(o, b), whole);
            std::reverse(b.begin(), b.end());
            expectSameAsset(assemble(o, b), whole);
            std::shuffle(b.begin(), b.end(), random);
            expectSameAsset(assemble(o, b), whole);
        }
    }
}

TEST_F(LightFieldRowsTest, MissingOrOverlappingRowsAreRefusedNamingThem) {
    const LightFieldBakeOptions o = options();
    std::vector<LightFieldRows> b = blocks(o, 2);
    const LightFieldRows extra = b[1]; // slab 0 rows 2 .. 2
    b.erase(b.begin() + 1);
    try {
        assemble(o, b);
        FAIL() << "assembled with rows missing";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("camera rows missing: slab 0 row 2"),
                  std::string::npos)
            << e.what();
    }
    b.push_back(extra);
    b.push_back(traceLightFieldRows(scene_->registry, scene_->markup, o, 4, 1, 3));
    try {
        assemble(o, b);
        FAIL() << "assembled with rows twice";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("slab 4 camera row 1 is also in"), std::string::npos)
            << e.what();
    }
}

TEST_F(LightFieldRowsTest, TheFileRoundTripsAndRefusesWhatIsWrongNamingIt) {
    const LightFieldBakeOptions o = options();
    const LightFieldRows r = traceLightFieldRows(scene_->registry, scene_->markup, o, 3, 1, 3);
    const std::string file = (root_ / "block.rows").string();
    writeLightFieldRows(r, file);
    const LightFieldRows back = readLightFieldRows(file, 3, 1, 3, 3, 8);
    EXPECT_TRUE(back.rgb == r.rgb);
    EXPECT_TRUE(back.histogram.bins == r.histogram.bins);
    EXPECT_EQ(back.histogram.total, r.histogram.total);
    EXPECT_GT(r.histogram.total, 0u);
    EXPECT_TRUE(sameBits(back.histogram.minDepth, r.histogram.minDepth));

    auto refused = [&](const std::string& path, const std::string& what, int slab = 3) {
        try {
            readLightFieldRows(path, slab, 1, 3, 3, 8);
            ADD_FAILURE() << "read " << path;
        } catch (const Error& e) {
            EXPECT_EQ(e.file(), path);
            EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
        }
    };
    refused(file, "expected 2, got 3", 2); // another slab's block
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    const std::string cut = (root_ / "cut.rows").string();
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() - 5);
    refused(cut, "truncated");
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, 20);
    refused(cut, "truncated");
    std::ofstream(cut, std::ios::binary) << bytes + "x";
    refused(cut, "bytes after the block's end");
    std::string header = bytes;
    header[0] = 'X';
    std::ofstream(cut, std::ios::binary) << header;
    refused(cut, "SPLFROWS");
    std::string counts = bytes;
    counts[8 + 4 + 20 + 4] ^= 1; // the sky count: no longer adds up
    std::ofstream(cut, std::ios::binary) << counts;
    refused(cut, "do not add up");
    refused((root_ / "none.rows").string(), "cannot read file: no such file");
}

} // namespace
} // namespace specula
