// A compressed distance probe on disk (issue 36, item 3: `--compress bc6h`): the composite's
// radiance as a BC6H KTX2 cube, its distance a one-channel cube beside it, the manifest in
// asset format 3.0. Written and read back it holds exactly what compressComposite made (the
// decoded blocks, the stored distances); the half-or-float distance rule is the closed form
// of distance_compression.h; damaged or inconsistent files are refused naming the field.
#include "components/reflection_probe/distance/distance_compression.h"
#include "components/reflection_probe/distance/distance_glossy_chain.h"
#include "components/reflection_probe/distance/distance_gpu_probe.h"
#include "components/reflection_probe/distance/distance_layer_tiles.h"
#include "components/reflection_probe/distance/distance_probe.h"
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "components/reflection_probe/distance/writer/distance_probe_writer.h"
#include "components/reflection_probe/manifest_fields.h"
#include "engine/core/error.h"
#include "engine/image/bc6h.h"
#include "engine/image/ktx2.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace specula {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const char* const kCommittedProbe = SPECULA_SOURCE_DIR "/tests/fuzz/data/probe/manifest.json";

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// Every texel's composite distance set to `far` where it hits (the rest stay d_inf).
void setCompositeHits(DistanceProbeAsset& a, float far) {
    for (Image& face : a.layers[0].faces)
        for (std::size_t i = 3; i < face.pixels.size(); i += 4)
            if (face.pixels[i] < a.dInf) face.pixels[i] = far;
}

class CompressedProbe : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("specula-compressed-" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        original_ = readDistanceProbe(kCommittedProbe);
        compressed_ = original_;
        compressComposite(compressed_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string manifest() const { return (dir_ / "manifest.json").string(); }
    json writtenManifest() const {
        std::ifstream in(manifest());
        return json::parse(in);
    }
    // Rewrites the manifest, sealed over its new fields, as a writer of them would.
    void rewrite(json m) const {
        m.erase("seal");
        m["seal"] = manifestSeal(m);
        std::ofstream(manifest()) << m.dump(1);
    }
    // The Error reading the probe gives (fails the test when it reads).
    Error readError() const {
        try {
            readDistanceProbe(manifest());
        } catch (const Error& e) {
            return e;
        }
        ADD_FAILURE() << "the damaged probe was read";
        return Error("", "", "");
    }

    fs::path dir_;
    DistanceProbeAsset original_, compressed_;
};

TEST_F(CompressedProbe, ReadsBackExactlyWhatWasCompressedInFormatThree) {
    ASSERT_EQ(compressed_.compression, DistanceCompression::Bc6h);
    // The committed probe reaches 4.9 m: a half's step there is 2^(2-10) = 3.9 mm <= 1 cm.
    EXPECT_TRUE(compressed_.halfCompositeDistance);
    writeDistanceProbe(compressed_, dir_.string(), "scene.gltf");
    const json m = writtenManifest();
    EXPECT_EQ(m["format"]["major"], 3);
    EXPECT_EQ(m["compression"], "bc6h");
    const DistanceProbeAsset back = readDistanceProbe(manifest());
    EXPECT_EQ(back.compression, DistanceCompression::Bc6h);
    EXPECT_TRUE(back.halfCompositeDistance);
    EXPECT_EQ(back.compositeBlocks, compressed_.compositeBlocks);
    // The object layers as an uncompressed probe stores them (half floats), the composite as
    // compressComposite left it.
    const DistanceProbeAsset stored = storedDistanceAsset(compressed_);
    ASSERT_EQ(back.layers.size(), original_.layers.size());
    for (std::size_t i = 0; i < back.layers.size(); ++i)
        for (int f = 0; f < 6; ++f)
            EXPECT_TRUE(sameBits(back.layers[i].faces[std::size_t(f)].pixels,
                                 stored.layers[i].faces[std::size_t(f)].pixels))
                << "layer " << i << " face " << f;
    // The radiance file is BC6H, the distance file one half-float channel. (On these 2^2
    // faces a block holds 4 texels, not 16: the 128^2 room shows the saving,
    // distance_compressed_gpu_test.cpp.)
    const Ktx2Texture radiance = readKtx2((dir_ / "layer_00.ktx2").string());
    const Ktx2Texture distance = readKtx2((dir_ / "layer_00_distance.ktx2").string());
    EXPECT_TRUE(radiance.bc6h);
    EXPECT_TRUE(distance.halfFloat);
    EXPECT_EQ(distance.levels[0].channels, 1);
    const int n = back.faceRes;
    EXPECT_EQ(compositeBytes(back), 6 * (bc6hBytes(n, n) + std::size_t(n * n) * 2));
}

// The committed probe with the GGX chain the bake would cook (glossyChainOf prefilters the
// float composite, as the bake does before it compresses), then compressed.
DistanceProbeAsset compressedWithGlossy(const DistanceProbeAsset& original) {
    DistanceProbeAsset a = original;
    CubeChain chain = glossyChainOf(a);
    a.glossyLevels.assign(chain.levels.begin() + 1, chain.levels.end());
    compressComposite(a);
    return a;
}

TEST_F(CompressedProbe, GlossyLevelsAreStoredAsBc6hAndReadBackExactly) {
    const DistanceProbeAsset glossy = compressedWithGlossy(original_);
    ASSERT_GE(glossy.glossyLevels.size(), 2u);
    ASSERT_EQ(glossy.glossyBlocks.size(), glossy.glossyLevels.size());
    for (std::size_t k = 0; k < glossy.glossyLevels.size(); ++k) {
        const int n = glossy.glossyLevels[k][0].width;
        EXPECT_EQ(glossy.glossyBlocks[k].size(), 6 * bc6hBytes(n, n)) << "level " << k + 1;
    }
    writeDistanceProbe(glossy, dir_.string(), "scene.gltf");
    const DistanceProbeAsset back = readDistanceProbe(manifest());
    EXPECT_EQ(back.glossyBlocks, glossy.glossyBlocks);
    ASSERT_EQ(back.glossyLevels.size(), glossy.glossyLevels.size());
    for (std::size_t k = 0; k < back.glossyLevels.size(); ++k) {
        // The file holds the blocks alone: RGB is their decoding, A the nearest composite
        // distance under each texel, bit for bit what compressComposite left in memory.
        EXPECT_TRUE(
            readKtx2((dir_ / ("layer_00_ggx_" + std::to_string(k + 1) + ".ktx2")).string()).bc6h)
            << "level " << k + 1;
        for (int f = 0; f < 6; ++f)
            EXPECT_TRUE(sameBits(back.glossyLevels[k][std::size_t(f)].pixels,
                                 glossy.glossyLevels[k][std::size_t(f)].pixels))
                << "level " << k + 1 << " face " << f;
    }
    // What the blocks hold is the float level's radiance within the codec's error.
    DistanceProbeAsset floatGlossy = original_;
    const CubeChain chain = glossyChainOf(floatGlossy);
    double sumSq = 0.0, sum = 0.0;
    long count = 0;
    for (std::size_t k = 0; k < back.glossyLevels.size(); ++k)
        for (int f = 0; f < 6; ++f) {
            const Image& want = chain.levels[k + 1][std::size_t(f)];
            const Image& got = back.glossyLevels[k][std::size_t(f)];
            for (std::size_t t = 0; t < want.pixels.size(); t += 4)
                for (std::size_t c = 0; c < 3; ++c) {
                    const double e = double(got.pixels[t + c]) - want.pixels[t + c];
                    sumSq += e * e, sum += want.pixels[t + c], ++count;
                }
        }
    const double rmse = std::sqrt(sumSq / double(count)), mean = sum / double(count);
    EXPECT_LT(rmse, 0.05 * mean) << "rmse " << rmse << " of mean radiance " << mean;
}

TEST_F(CompressedProbe, TheWriterRefusesGlossyBlocksThatDoNotHoldTheLevelAndWritesNothing) {
    DistanceProbeAsset glossy = compressedWithGlossy(original_);
    glossy.glossyLevels[0][4].at(0, 0)[1] += 0.5f;
    try {
        writeDistanceProbe(glossy, dir_.string(), "scene.gltf");
        FAIL() << "written";
    } catch (const Error& e) {
        EXPECT_EQ(e.field(), "radiance");
        EXPECT_NE(std::string(e.what()).find("layer_00_ggx_1.ktx2"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(dir_));
    glossy = compressedWithGlossy(original_);
    glossy.glossyBlocks.pop_back();
    EXPECT_THROW(writeDistanceProbe(glossy, dir_.string(), "scene.gltf"), Error);
    EXPECT_FALSE(fs::exists(dir_));
}

TEST_F(CompressedProbe, CompressionKeepsRadianceCloseAndDistancesWithinHalfAStep) {
    double worstDistance = 0.0, sum = 0.0, sumSq = 0.0;
    int n = 0;
    for (int f = 0; f < 6; ++f) {
        const Image& a = original_.layers[0].faces[std::size_t(f)];
        const Image& b = compressed_.layers[0].faces[std::size_t(f)];
        for (std::size_t t = 0; t < a.pixels.size(); t += 4) {
            for (std::size_t c = 0; c < 3; ++c) {
                const double e = double(b.pixels[t + c]) - a.pixels[t + c];
                sumSq += e * e, sum += a.pixels[t + c], ++n;
            }
            const double d = a.pixels[t + 3];
            worstDistance = std::max(worstDistance, std::fabs(b.pixels[t + 3] - d) / d);
        }
    }
    // Round to nearest: within half a half's step, 2^-11 relative.
    EXPECT_LE(worstDistance, std::ldexp(1.0, -11));
    const double rmse = std::sqrt(sumSq / n), mean = sum / n;
    EXPECT_LT(rmse, 0.05 * mean) << "rmse " << rmse << " of mean radiance " << mean;
    // Layer 0's figures are restated from what is stored: the reader's own measure.
    const DistanceLayerContent c =
        measureDistanceLayer(compressed_.layers[0].faces, compressed_.dInf, "layer 0");
    EXPECT_EQ(compressed_.layers[0].maxDistance, c.maxDistance);
    EXPECT_EQ(compressed_.layers[0].minDistance, c.minDistance);
}

TEST_F(CompressedProbe, HalfDistancesOnlyWhereAHalfsStepIsWithinTheTolerance) {
    // d_max 3 m: step 2^(1-10) = 2 mm; 43 m (zdm2's composite): 2^(5-10) = 31 mm.
    DistanceProbeAsset a = original_;
    setCompositeHits(a, 3.f);
    EXPECT_TRUE(compositeDistanceFitsHalf(a, 0.01f));
    EXPECT_FALSE(compositeDistanceFitsHalf(a, 0.001f));
    setCompositeHits(a, 43.f);
    EXPECT_FALSE(compositeDistanceFitsHalf(a, 0.01f));
    EXPECT_TRUE(compositeDistanceFitsHalf(a, std::ldexp(1.f, -5)));
    // A d_inf no half holds exactly would lose the sentinel.
    a.dInf = 1000.3f;
    EXPECT_FALSE(compositeDistanceFitsHalf(a, 1.f));
    // The d_e the rule is held to: the measured plan's when it recorded one, else the
    // component's default.
    DistanceProbeAsset planned = original_;
    planned.effectPlan.clear();
    EXPECT_EQ(cookedLookupTolerance(planned), DistanceProbe{}.errorTolerance);
    planned.effectPlan = R"({"lookup": {"tolerance": 0.05}})";
    EXPECT_EQ(cookedLookupTolerance(planned), 0.05f);
}

TEST_F(CompressedProbe, AFarCompositeKeepsFloatDistancesAndReadsBackExactly) {
    DistanceProbeAsset far = original_;
    for (DistanceProbeLayer& L : far.layers)
        for (Image& face : L.faces)
            for (std::size_t i = 3; i < face.pixels.size(); i += 4)
                if (face.pixels[i] < far.dInf) face.pixels[i] *= 10.f; // up to 49 m
    for (DistanceProbeLayer& L : far.layers) {
        const DistanceLayerContent c = measureDistanceLayer(L.faces, far.dInf, "");
        L.minDistance = c.minDistance, L.maxDistance = c.maxDistance;
        L.avgDistance = std::clamp(L.avgDistance * 10.f, c.minDistance, c.maxDistance);
    }
    compressComposite(far);
    EXPECT_FALSE(far.halfCompositeDistance);
    writeDistanceProbe(far, dir_.string(), "scene.gltf");
    EXPECT_FALSE(readKtx2((dir_ / "layer_00_distance.ktx2").string()).halfFloat);
    const DistanceProbeAsset back = readDistanceProbe(manifest());
    for (int f = 0; f < 6; ++f) // float32 distances, exactly as baked
        for (std::size_t t = 3; t < back.layers[0].faces[0].pixels.size(); t += 4)
            ASSERT_EQ(back.layers[0].faces[std::size_t(f)].pixels[t],
                      far.layers[0].faces[std::size_t(f)].pixels[t]);
}

TEST_F(CompressedProbe, TheWriterRefusesBlocksThatDoNotHoldTheRadianceAndWritesNothing) {
    compressed_.layers[0].faces[2].at(1, 1)[0] += 0.5f;
    try {
        writeDistanceProbe(compressed_, dir_.string(), "scene.gltf");
        FAIL() << "written";
    } catch (const Error& e) {
        EXPECT_EQ(e.field(), "radiance");
        EXPECT_NE(std::string(e.what()).find("face +Y texel (1, 1)"), std::string::npos)
            << e.what();
    }
    EXPECT_FALSE(fs::exists(dir_));
}

TEST_F(CompressedProbe, CompressionInAFormatTwoManifestIsRefused) {
    writeDistanceProbe(compressed_, dir_.string(), "scene.gltf");
    json m = writtenManifest();
    m["format"]["major"] = 2;
    m["format"]["minor"] = 1;
    rewrite(m);
    const Error e = readError();
    EXPECT_EQ(e.field(), "compression");
    EXPECT_NE(std::string(e.what()).find("needs asset format 3.0"), std::string::npos) << e.what();
    m["format"]["major"] = 3;
    m["compression"] = "bc7";
    rewrite(m);
    EXPECT_EQ(readError().field(), "compression");
}

TEST_F(CompressedProbe, ADamagedOrMissingDistanceFileIsRefusedNamingIt) {
    writeDistanceProbe(compressed_, dir_.string(), "scene.gltf");
    const fs::path distance = dir_ / "layer_00_distance.ktx2";
    {
        // One distance's last byte changed: the file still parses, its checksum differs.
        std::fstream f(distance, std::ios::in | std::ios::out | std::ios::binary);
        f.seekg(-1, std::ios::end);
        char last = 0;
        f.get(last);
        f.seekp(-1, std::ios::end);
        f.put(char(last ^ 0x5a));
    }
    Error e = readError();
    EXPECT_EQ(e.field(), "layers[0].distance.checksum") << e.what();
    fs::remove(distance);
    e = readError();
    EXPECT_EQ(e.field(), "layers[0].distance.file") << e.what();
}

TEST_F(CompressedProbe, ARadianceFileThatIsNotBc6hIsRefused) {
    writeDistanceProbe(compressed_, dir_.string(), "scene.gltf");
    // An RGB float cube in place of the blocks, its checksum restated: a forged asset.
    const int n = compressed_.faceRes;
    Image rgb(n, 6 * n, 3);
    writeKtx2((dir_ / "layer_00.ktx2").string(), Ktx2Texture{.cube = true, .levels = {rgb}});
    json m = writtenManifest();
    m["layers"][0]["checksum"] = fileChecksum((dir_ / "layer_00.ktx2").string());
    rewrite(m);
    const Error e = readError();
    EXPECT_EQ(e.field(), "vkFormat") << e.what();
    EXPECT_NE(std::string(e.what()).find("BC6H"), std::string::npos) << e.what();
}

// A glossy level of a compressed probe that holds floats, not blocks (its checksum restated):
// refused naming the level's file and its vkFormat.
TEST_F(CompressedProbe, AGlossyLevelThatIsNotBc6hIsRefusedNamingIt) {
    const DistanceProbeAsset glossy = compressedWithGlossy(original_);
    writeDistanceProbe(glossy, dir_.string(), "scene.gltf");
    const fs::path level = dir_ / "layer_00_ggx_1.ktx2";
    const int n = glossy.glossyLevels[0][0].width;
    writeKtx2Cube(level.string(), Image(n, 6 * n, 4));
    json m = writtenManifest();
    m["glossy"]["levels"][0]["checksum"] = fileChecksum(level.string());
    rewrite(m);
    const Error e = readError();
    EXPECT_EQ(e.field(), "glossy.levels[0].vkFormat") << e.what();
    EXPECT_NE(std::string(e.what()).find("layer_00_ggx_1.ktx2"), std::string::npos) << e.what();
}

} // namespace
} // namespace specula
