// The glTF loader on bad files: truncated, mislabelled or corrupt bytes, missing buffers,
// accessors and indices out of range, URIs that are directories, FIFOs or devices, scenes that
// are directories or symlink loops, byte flips: each refused with a specula::Error naming the
// file and the fault. Good files loaded: gltf_loader_test.cpp.
#include "engine/core/error.h"
#include "engine/ecs/registry.h"
#include "engine/scene/gltf_loader.h"
#include "gltf_loader_fixture.h"
#include "numerics/bad_input_support.h"
#include "support/gltf_load_error.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/stat.h>
#include <tuple>
#include <vector>

namespace fs = std::filesystem;
using namespace specula;

namespace {

using test::gltf_files::gltfJson;
using test::gltf_files::kRoom;
using test::gltf_files::kScenes;
using test::gltf_files::le32;
using test::gltf_files::readBytes;
using test::gltf_files::TempDir;

void writeBytes(const fs::path& p, const std::vector<unsigned char>& b) {
    std::ofstream out(p, std::ios::binary);
    out.write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
}

using test::expectLoadError;

} // namespace

TEST(GltfLoaderErrors, TruncatedGlb) {
    TempDir dir;
    auto b = readBytes(kScenes / "box/Box.glb");
    b.resize(b.size() / 2);
    writeBytes(dir.path() / "truncated.glb", b);
    expectLoadError(dir.path() / "truncated.glb", "truncated chunk");
}

TEST(GltfLoaderErrors, WrongMagic) {
    TempDir dir;
    auto b = readBytes(kScenes / "box/Box.glb");
    std::memcpy(b.data(), "gLTF", 4);
    writeBytes(dir.path() / "magic.glb", b);
    expectLoadError(dir.path() / "magic.glb", "bad magic: expected 'glTF'");
}

TEST(GltfLoaderErrors, MissingBuffer) {
    TempDir dir;
    fs::copy_file(kScenes / "box/Box.gltf", dir.path() / "Box.gltf");
    expectLoadError(dir.path() / "Box.gltf", "missing buffer: 'Box0.bin'");
}

TEST(GltfLoaderErrors, CorruptDracoPayload) {
    TempDir dir;
    auto b = readBytes(kScenes / "box/Box_Draco.glb");
    const auto j = gltfJson(kScenes / "box/Box_Draco.glb");
    const std::size_t binData = 20 + le32(b, 12) + 8;
    const int view =
        j["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["bufferView"];
    const auto& bv = j["bufferViews"][std::size_t(view)];
    const std::size_t start = binData + bv.value("byteOffset", std::size_t(0));
    for (std::size_t i = 0; i < bv["byteLength"].get<std::size_t>(); ++i)
        b[start + i] = static_cast<unsigned char>(b[start + i] * 37u + 11u);
    writeBytes(dir.path() / "corrupt_draco.glb", b);
    expectLoadError(dir.path() / "corrupt_draco.glb", "undecodable Draco payload");
}

TEST(GltfLoaderErrors, AccessorOutOfRange) {
    TempDir dir;
    auto j = gltfJson(kScenes / "box/Box.gltf");
    fs::copy_file(kScenes / "box/Box0.bin", dir.path() / "Box0.bin");
    j["accessors"][1]["count"] = 1000000;
    std::ofstream(dir.path() / "accessor.gltf") << j.dump();
    expectLoadError(dir.path() / "accessor.gltf", "accessor out of range");
}

TEST(GltfLoaderErrors, IndexOutOfRange) {
    TempDir dir;
    const auto j = gltfJson(kScenes / "box/Box.gltf");
    auto bin = readBytes(kScenes / "box/Box0.bin");
    const auto& acc = j["accessors"][j["meshes"][0]["primitives"][0]["indices"].get<std::size_t>()];
    ASSERT_EQ(acc["componentType"], 5123); // UNSIGNED_SHORT
    const auto& bv = j["bufferViews"][acc["bufferView"].get<std::size_t>()];
    const std::size_t at =
        bv.value("byteOffset", std::size_t(0)) + acc.value("byteOffset", std::size_t(0));
    bin[at] = 0xff; // index 0 becomes >= 255, far beyond the 24 vertices
    writeBytes(dir.path() / "Box0.bin", bin);
    std::ofstream(dir.path() / "index.gltf") << j.dump();
    expectLoadError(dir.path() / "index.gltf", "index out of range");
}

// The room copied into `dir` with images[0] (a texture the floor uses) or buffers[0] (as
// `field` says) pointing at `uri`.
fs::path roomPointingAt(const TempDir& dir, const std::string& field, const std::string& uri) {
    auto j = gltfJson(kRoom);
    for (const char* f : {"room.bin", "floor_tiles.png", "panel_stripes.png", "panel_grid.png"})
        fs::copy_file(kRoom.parent_path() / f, dir.path() / f, fs::copy_options::skip_existing);
    j[field][0]["uri"] = uri;
    const fs::path out = dir.path() / ("room_" + field + ".gltf");
    std::ofstream(out) << j.dump();
    return out;
}

// tinygltf's default reader took URI "." (a directory) as SIZE_MAX bytes: std::bad_alloc.
TEST(GltfLoaderErrors, ImageUriThatIsADirectoryIsNamed) {
    TempDir dir;
    const fs::path gltf = roomPointingAt(dir, "images", ".");
    expectLoadError(gltf, "images[0].uri");
    expectLoadError(gltf, "cannot read image '.'");
}

TEST(GltfLoaderErrors, ImageOrBufferThatIsAFifoOrDeviceIsRefusedWithoutBlocking) {
    TempDir dir;
    ASSERT_EQ(::mkfifo((dir.path() / "pipe").c_str(), 0600), 0);
    fs::create_symlink("/dev/zero", dir.path() / "zero");
    for (const auto& [field, uri, part] :
         {std::tuple<std::string, std::string, std::string>{"images", "pipe", "images[0].uri"},
          {"buffers", "pipe", "FIFO"},
          {"images", "zero", "images[0].uri"},
          {"buffers", "zero", "character device"}}) {
        const fs::path gltf = roomPointingAt(dir, field, uri);
        test::expectNames(test::errorOfInChild([&] {
                              ecs::Registry reg;
                              loadGltf(gltf.string(), reg);
                          }),
                          {gltf.filename().string(), part});
    }
}

TEST(GltfLoaderErrors, SceneThatIsADirectoryOrSymlinkLoopIsNamed) {
    TempDir dir;
    fs::create_directory(dir.path() / "scene.gltf");
    expectLoadError(dir.path() / "scene.gltf", "a directory");
    fs::create_symlink("loop.glb", dir.path() / "loop.glb");
    expectLoadError(dir.path() / "loop.glb", "symlink loop");
}

TEST(GltfLoaderErrors, UnreadableFile) {
    expectLoadError(fs::path("/nonexistent/specula/none.glb"), "cannot read file");
}

// Hostile bytes anywhere in a file give either a scene or a specula::Error, never a crash
// or another exception.
TEST(GltfLoaderErrors, ByteFlipsNeverEscapeAsAnythingButError) {
    TempDir dir;
    for (const char* file : {"box/Box.glb", "box/Box_Draco.glb"}) {
        const auto original = readBytes(kScenes / file);
        for (std::size_t at = 0; at < original.size(); at += 7) {
            auto b = original;
            b[at] ^= 0x5a;
            const fs::path p = dir.path() / "flipped.glb";
            writeBytes(p, b);
            ecs::Registry reg;
            try {
                loadGltf(p.string(), reg);
            } catch (const Error&) {
                EXPECT_EQ(reg.alive(), 0u);
            } catch (const std::exception& e) {
                ADD_FAILURE() << file << " byte " << at << ": " << e.what();
            }
        }
    }
}
