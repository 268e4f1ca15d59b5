#pragma once
// Helpers of the shard tests: the two-room level (two probes) and a level folder's files.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

namespace specula::test {

inline const std::string kTwoRooms =
    std::string(SPECULA_SOURCE_DIR) + "/assets/two_rooms/two_rooms.gltf";

// Every file under `dir` but the shard store, by relative path, with its bytes. Needs EXRs
// without OpenImageIO's wall-clock "DateTime" header (engine/image/image_io.cpp): with it,
// two bakes that straddle a second differ in that attribute and in the checksums over it.
inline std::map<std::string, std::string> treeBytes(const std::filesystem::path& dir) {
    namespace fs = std::filesystem;
    std::map<std::string, std::string> files;
    for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator();
         ++it) {
        if (it->path().filename() == ".shards") {
            it.disable_recursion_pending();
            continue;
        }
        if (!it->is_regular_file()) continue;
        std::ifstream in(it->path(), std::ios::binary);
        files[fs::relative(it->path(), dir).string()] =
            std::string(std::istreambuf_iterator<char>(in), {});
    }
    return files;
}

} // namespace specula::test
