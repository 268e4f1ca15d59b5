// Bad cooked light-field probes (issue 10): every manifest number range-checked and
// consistent with the others (cell, NUM, RES, atlas and file sizes, depths, disparity), slab
// files regular and exactly sized, BC1 blocks decodable; errors name the file and the field.
// The probes are made from a small synthetic asset (tests/fuzz/synthetic_lightfield.h), RGB8
// and BC1.
#include "bad_input_support.h"

#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "components/reflection_probe/lightfield/lightfield_asset.h"
#include "components/reflection_probe/lightfield/writer/lightfield_probe_writer.h"
#include "tests/fuzz/synthetic_lightfield.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <sys/stat.h>

namespace fs = std::filesystem;
using nlohmann::json;
using namespace specula;
using namespace specula::test;

namespace {

class BadLightField : public ::testing::TestWithParam<LightFieldCompression> {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("specula-bad-lightfield-" + std::to_string(::getpid()) +
                                            "-" + std::to_string(int(GetParam())));
        fs::remove_all(dir_);
        writeLightFieldProbe(smallLightField(GetParam()), dir_.string(), "synthetic");
        good_ = json::parse(slurp(manifest()));
    }
    void TearDown() override { fs::remove_all(dir_); }

    fs::path manifest() const { return dir_ / "manifest.json"; }
    fs::path slab(int k) const {
        return dir_ / good_["slabs"][std::size_t(k)]["file"].get<std::string>();
    }
    std::string readError() const {
        return errorOf([&] { readLightFieldProbe(manifest().string()); });
    }
    void refused(const std::function<void(json&)>& edit, std::initializer_list<std::string> parts) {
        json m = good_;
        edit(m);
        spit(manifest(), m.dump(2));
        expectNames(readError(), parts);
    }

    fs::path dir_;
    json good_;
};

TEST_P(BadLightField, GoodOneReads) {
    const LightFieldAsset a = readLightFieldProbe(manifest().string());
    EXPECT_EQ(a.atlasSize(), 8);
    EXPECT_EQ(a.slabs[3].data, smallLightField(GetParam()).slabs[3].data);
    ASSERT_EQ(a.intrusions.size(), 1u);
    EXPECT_EQ(a.intrusions[0].object, "pillar");
}

TEST_P(BadLightField, NumbersAreRangeChecked) {
    refused([](json& m) { m["cell"]["centre"] = {1e308, 0, 0}; }, {"manifest.json", "cell.centre"});
    refused([](json& m) { m["cell"]["centre"] = {0, 0, 1.5e7}; }, {"manifest.json", "cell.centre"});
    refused([](json& m) { m["cameras"] = 2.5; }, {"manifest.json", "cameras", "integer"});
    refused([](json& m) { m["image_res"] = 6; }, {"manifest.json", "image_res"});
    refused([](json& m) { m["fov_deg"] = 60; }, {"manifest.json", "fov_deg"});
    refused([](json& m) { m["camera_spacing"] = 1.0; }, {"manifest.json", "camera_spacing"});
    refused([](json& m) { m["bake"]["seconds"] = -1; }, {"manifest.json", "bake.seconds"});
    refused([](json& m) { m["intrusions"][0]["depth_m"] = "deep"; },
            {"manifest.json", "intrusions[0].depth_m"});
}

TEST_P(BadLightField, AtlasAndFileSizesAreExactForTheCompression) {
    refused([](json& m) { m["atlas"]["width"] = 16; }, {"manifest.json", "atlas"});
    refused([](json& m) { m["atlas"]["layers"] = 5; }, {"manifest.json", "atlas.layers"});
    refused([](json& m) { m["slabs"][2]["bytes"] = m["slabs"][2]["bytes"].get<int>() + 1; },
            {"manifest.json", "slabs[2].bytes"});
    // A slab file one byte short, checksum updated: refused by size.
    std::string bytes = slurp(slab(4));
    bytes.pop_back();
    spit(slab(4), bytes);
    refused([&](json& m) { m["slabs"][4]["checksum"] = fileChecksum(slab(4).string()); },
            {"slab_zpos", "size"});
}

TEST_P(BadLightField, SlabDepthsMustAgreeWithEachOther) {
    refused([](json& m) { m["slabs"][0]["depth_near"] = 5.0; },
            {"manifest.json", "slabs[0].depth_near"});
    refused([](json& m) { m["slabs"][1]["focal_depth"] = 9.0; },
            {"manifest.json", "slabs[1].focal_depth"});
    refused([](json& m) { m["slabs"][5]["disparity_px"] = 3.0; },
            {"manifest.json", "slabs[5].disparity_px"});
    refused([](json& m) { m["slabs"][3]["depth_min"] = 7.0; },
            {"manifest.json", "slabs[3].depth_min"});
    refused([](json& m) { m["slabs"][3]["sky_fraction"] = 0.99; },
            {"manifest.json", "slabs[3].sky_fraction"});
    spit(manifest(), withRawValue(good_, "disparity_px", "-1e999"));
    expectNames(readError(), {"manifest.json: disparity_px: number out of range"});
}

TEST_P(BadLightField, SlabFileThatIsAFifoIsRefusedWithoutBlocking) {
    fs::remove(slab(1));
    ASSERT_EQ(::mkfifo(slab(1).c_str(), 0600), 0);
    expectNames(errorOfInChild([&] { readLightFieldProbe(manifest().string()); }),
                {"manifest.json", "slabs[1].file", "FIFO"});
}

TEST_P(BadLightField, SlabFileThatIsADirectoryOrDevZeroIsNamed) {
    fs::remove(slab(2));
    fs::create_directory(slab(2));
    expectNames(readError(), {"manifest.json", "slabs[2].file", "a directory"});
    fs::remove(slab(2));
    fs::create_symlink("/dev/zero", slab(2));
    expectNames(errorOfInChild([&] { readLightFieldProbe(manifest().string()); }),
                {"manifest.json", "slabs[2].file", "character device"});
}

INSTANTIATE_TEST_SUITE_P(Compression, BadLightField,
                         ::testing::Values(LightFieldCompression::None, LightFieldCompression::BC1),
                         [](const auto& info) { return std::string(toString(info.param)); });

TEST(BadLightFieldBC1, UndecodableBlockIsRefused) {
    const fs::path dir =
        fs::temp_directory_path() / ("specula-bad-bc1-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    writeLightFieldProbe(smallLightField(LightFieldCompression::BC1), dir.string(), "synthetic");
    json m = json::parse(slurp(dir / "manifest.json"));
    const fs::path slab = dir / m["slabs"][0]["file"].get<std::string>();
    std::string bytes = slurp(slab);
    // Block 3: c0 < c1 (three-colour mode) and texel 0 uses index 3 (transparent black).
    bytes[24] = 0x00, bytes[25] = 0x10, bytes[26] = 0x00, bytes[27] = 0x20, bytes[28] = 0x03;
    spit(slab, bytes);
    m["slabs"][0]["checksum"] = fileChecksum(slab.string());
    spit(dir / "manifest.json", m.dump());
    expectNames(errorOf([&] { readLightFieldProbe((dir / "manifest.json").string()); }),
                {"slab_xpos.bc1", "texels", "BC1 block 3"});
    // The writer refuses the same atlas.
    LightFieldAsset a = smallLightField(LightFieldCompression::BC1);
    a.slabs[0].data.assign(bytes.begin(), bytes.end());
    expectNames(errorOf([&] { writeLightFieldProbe(a, (dir / "never").string(), "synthetic"); }),
                {"slabs[0]", "BC1 block 3"});
    EXPECT_FALSE(fs::exists(dir / "never"));
    fs::remove_all(dir);
}

} // namespace
