// Object layers on disk as RGBA16F (issue 36, item 2): the runtime already rounds them to half
// floats for the GPU (storedDistanceAsset), so writing them as half loses nothing it uses.
// The committed probe (five object layers) written and read back: every object layer is a
// VK_FORMAT_R16G16B16A16_SFLOAT file holding exactly the stored (half-rounded) values, the
// composite stays float32 and exact, and the object layers take half the bytes.
#include "components/reflection_probe/distance/distance_gpu_probe.h"
#include "components/reflection_probe/distance/distance_layer_tiles.h"
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "components/reflection_probe/distance/writer/distance_probe_writer.h"
#include "engine/image/ktx2.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <unistd.h>

namespace specula {
namespace {

namespace fs = std::filesystem;

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

TEST(HalfLayersFile, ObjectLayersAreWrittenAsTheHalfFloatsTheRuntimeStores) {
    const DistanceProbeAsset original =
        readDistanceProbe(SPECULA_SOURCE_DIR "/tests/fuzz/data/probe/manifest.json");
    ASSERT_GT(original.layers.size(), 1u);
    ASSERT_TRUE(objectLayersFitHalf(original));
    const fs::path dir =
        fs::temp_directory_path() / ("specula-half-layers-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    writeDistanceProbe(original, dir.string(), "scene.gltf");
    const DistanceProbeAsset back = readDistanceProbe((dir / "manifest.json").string());
    const DistanceProbeAsset stored = storedDistanceAsset(original);
    ASSERT_EQ(back.layers.size(), original.layers.size());
    for (std::size_t i = 0; i < back.layers.size(); ++i) {
        const Ktx2Texture file = readKtx2((dir / back.layers[i].file).string());
        EXPECT_EQ(file.halfFloat, i > 0) << "layer " << i;
        for (int f = 0; f < 6; ++f)
            EXPECT_TRUE(sameBits(back.layers[i].faces[std::size_t(f)].pixels,
                                 stored.layers[i].faces[std::size_t(f)].pixels))
                << "layer " << i << " face " << f;
        if (i > 0) {
            EXPECT_LT(fs::file_size(dir / back.layers[i].file),
                      fs::file_size(dir / back.layers[0].file));
        }
    }
    // The composite is float32 as baked.
    for (int f = 0; f < 6; ++f)
        EXPECT_TRUE(sameBits(back.layers[0].faces[std::size_t(f)].pixels,
                             original.layers[0].faces[std::size_t(f)].pixels));
    fs::remove_all(dir);
}

// A scene modelled a million times smaller: its distances fall below half's smallest normal
// (2^-14), where a half keeps too few bits to order the layers. Such layers stay float32.
TEST(HalfLayersFile, DistancesBelowHalfsNormalRangeKeepTheLayersFloat) {
    DistanceProbeAsset tiny =
        readDistanceProbe(SPECULA_SOURCE_DIR "/tests/fuzz/data/probe/manifest.json");
    const auto scaleDistances = [](std::array<Image, 6>& faces) {
        for (Image& face : faces)
            for (std::size_t i = 3; i < face.pixels.size(); i += std::size_t(face.channels))
                face.pixels[i] *= 1e-6f;
    };
    tiny.dInf *= 1e-6f;
    tiny.range *= 1e-6f;
    tiny.centre *= 1e-6f;
    tiny.boxMin *= 1e-6f;
    tiny.boxMax *= 1e-6f;
    for (auto& layer : tiny.layers) {
        scaleDistances(layer.faces);
        const DistanceLayerContent content = measureDistanceLayer(layer.faces, tiny.dInf, "");
        layer.minDistance = content.minDistance;
        layer.maxDistance = content.maxDistance;
        layer.avgDistance *= 1e-6f;
        layer.boxMin *= 1e-6f;
        layer.boxMax *= 1e-6f;
    }
    for (auto& level : tiny.glossyLevels)
        scaleDistances(level);
    EXPECT_FALSE(objectLayersFitHalf(tiny));
    const fs::path dir =
        fs::temp_directory_path() / ("specula-tiny-layers-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    writeDistanceProbe(tiny, dir.string(), "scene.gltf");
    const DistanceProbeAsset back = readDistanceProbe((dir / "manifest.json").string());
    for (std::size_t i = 0; i < back.layers.size(); ++i) {
        EXPECT_FALSE(readKtx2((dir / back.layers[i].file).string()).halfFloat) << "layer " << i;
        for (int f = 0; f < 6; ++f)
            EXPECT_TRUE(sameBits(back.layers[i].faces[std::size_t(f)].pixels,
                                 tiny.layers[i].faces[std::size_t(f)].pixels))
                << "layer " << i << " face " << f;
    }
    fs::remove_all(dir);
}

} // namespace
} // namespace specula
