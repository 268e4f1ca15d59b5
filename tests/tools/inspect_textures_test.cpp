// `specula-cook inspect` of cooked textures (issue 36: EXR stays only as a debug dump): a folder
// of KTX2 files is listed with each one's format, size, levels and bytes, and --dump-exr writes
// every level as OpenEXR holding exactly what the KTX2 holds (BC6H decoded). Refusals (a
// folder without textures, a damaged one, --dump-exr of a scene): bad_input_test.cpp.
#include "assetcooker/lib/cli/cli.h"
#include "engine/image/bc6h.h"
#include "engine/image/ktx2.h"
#include "engine/image_io/image_io.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace specula {
namespace {

namespace fs = std::filesystem;

Image ramp(int w, int h, int channels) {
    Image img(w, h, channels);
    for (std::size_t i = 0; i < img.pixels.size(); ++i)
        img.pixels[i] = 0.25f + float(i % 97) * 1.5f;
    return img;
}

struct CookRun {
    int status;
    std::string out, err;
};

CookRun cook(const std::vector<std::string>& args) {
    std::ostringstream out, err;
    const int status = cook::runCli(args, out, err);
    return {status, out.str(), err.str()};
}

TEST(InspectTextures, ListsAFoldersKtx2FilesAndDumpsThemAsExr) {
    const fs::path dir =
        fs::temp_directory_path() / ("specula-inspect-" + std::to_string(getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir / "probe");
    const Ktx2Texture cube{.cube = true, .levels = {ramp(4, 24, 4), ramp(2, 12, 4), ramp(1, 6, 4)}};
    writeKtx2((dir / "probe" / "layer_00.ktx2").string(), cube);
    const Ktx2Texture bc6h{.bc6h = true, .levels = {ramp(8, 8, 3)}};
    writeKtx2((dir / "probe" / "sample_00.ktx2").string(), bc6h);

    const CookRun r = cook({"inspect", dir.string(), "--dump-exr", (dir / "exr").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    ASSERT_EQ(j["textures"].size(), 2u);
    const nlohmann::json& a = j["textures"][0];
    EXPECT_EQ(a["file"], "probe/layer_00.ktx2");
    EXPECT_EQ(a["format"], "RGBA32F");
    EXPECT_EQ(a["cube"], true);
    EXPECT_EQ(a["width"], 4);
    EXPECT_EQ(a["height"], 4);
    EXPECT_EQ(a["levels"], 3);
    EXPECT_EQ(a["bytes"], fs::file_size(dir / "probe" / "layer_00.ktx2"));
    EXPECT_EQ(j["textures"][1]["format"], "BC6H");
    EXPECT_EQ(j["bytes"], fs::file_size(dir / "probe" / "layer_00.ktx2") +
                              fs::file_size(dir / "probe" / "sample_00.ktx2"));
    ASSERT_EQ(j["exr"].size(), 4u); // three cube levels and the BC6H image

    // The dump holds the textures' values: the float cube exactly, BC6H as decoded.
    EXPECT_EQ(readFloatExr((dir / "exr" / "probe" / "layer_00_mip1.exr").string()).pixels,
              cube.levels[1].pixels);
    const Image decoded = decodeBC6H(encodeBC6H(bc6h.levels[0]), 8, 8);
    EXPECT_EQ(readFloatExr((dir / "exr" / "probe" / "sample_00.exr").string()).pixels,
              decoded.pixels);
    fs::remove_all(dir);
}

} // namespace
} // namespace specula
