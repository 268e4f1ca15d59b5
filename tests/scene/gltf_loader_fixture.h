#pragma once
// The glTF files of the loader tests: their paths, their bytes and JSON, a scratch folder.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <unistd.h>
#include <vector>

namespace specula::test::gltf_files {

inline const std::filesystem::path kScenes = SPECULA_TEST_SCENES;
inline const std::filesystem::path kRoom =
    std::filesystem::path(SPECULA_SOURCE_DIR) / "assets" / "room" / "room.gltf";

inline std::vector<unsigned char> readBytes(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
inline std::uint32_t le32(const std::vector<unsigned char>& b, std::size_t at) {
    std::uint32_t v;
    std::memcpy(&v, b.data() + at, 4);
    return v;
}

// The glTF JSON of a .gltf or .glb, parsed independently of the loader.
inline nlohmann::json gltfJson(const std::filesystem::path& p) {
    const auto b = readBytes(p);
    if (b.size() >= 4 && std::memcmp(b.data(), "glTF", 4) == 0)
        return nlohmann::json::parse(b.begin() + 20, b.begin() + 20 + le32(b, 12));
    return nlohmann::json::parse(b.begin(), b.end());
}

// A scratch folder per test, removed afterwards.
class TempDir {
public:
    TempDir() {
        path_ = std::filesystem::temp_directory_path() /
                ("specula_scene_test_" + std::to_string(::getpid()) + "_" +
                 ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDir() { std::filesystem::remove_all(path_); }
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

} // namespace specula::test::gltf_files
