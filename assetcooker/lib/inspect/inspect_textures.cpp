#include "assetcooker/lib/inspect/inspect_textures.h"

#include "engine/core/error.h"
#include "engine/image/ktx2.h"
#include "engine/image_io/image_io.h"

#include <algorithm>
#include <filesystem>
#include <vector>

namespace specula::cook {

namespace fs = std::filesystem;

namespace {

std::string formatName(const Ktx2Texture& t) {
    if (t.bc6h) return "BC6H";
    static const char* const channels[] = {"R", "RG", "RGB", "RGBA"};
    return std::string(channels[t.levels.front().channels - 1]) + (t.halfFloat ? "16F" : "32F");
}

std::vector<fs::path> ktx2Files(const fs::path& root) {
    std::vector<fs::path> files;
    if (!fs::is_directory(root)) return {root};
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(root))
        if (e.is_regular_file() && e.path().extension() == ".ktx2") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
}

} // namespace

bool isCookedTexturePath(const std::string& path) {
    std::error_code ec;
    return fs::is_directory(path, ec) || fs::path(path).extension() == ".ktx2";
}

nlohmann::json inspectTextures(const std::string& path, const std::string& exrDir) {
    const fs::path root(path);
    if (!fs::exists(root)) throw Error(path, "", "no such file or folder");
    nlohmann::json list = nlohmann::json::array(), exr = nlohmann::json::array();
    std::uintmax_t total = 0;
    const std::vector<fs::path> files = ktx2Files(root);
    if (files.empty())
        throw Error(path, "",
                    "no KTX2 texture in this folder (inspect takes a glTF/GLB scene, a "
                    "cooked probe or level folder, or a .ktx2 file)");
    for (const fs::path& file : files) {
        const Ktx2Texture t = readKtx2(file.string());
        const std::string rel =
            fs::is_directory(root) ? fs::relative(file, root).string() : file.filename().string();
        const std::uintmax_t bytes = fs::file_size(file);
        total += bytes;
        const int faces = t.cube ? 6 : 1;
        list.push_back({{"file", rel},
                        {"format", formatName(t)},
                        {"cube", t.cube},
                        {"width", t.levels.front().width},
                        {"height", t.levels.front().height / faces},
                        {"levels", t.levels.size()},
                        {"bytes", bytes}});
        if (exrDir.empty()) continue;
        for (std::size_t k = 0; k < t.levels.size(); ++k) {
            fs::path out = fs::path(exrDir) / rel;
            out.replace_extension();
            out += (k ? "_mip" + std::to_string(k) : std::string()) + ".exr";
            fs::create_directories(out.parent_path());
            writeImage(out.string(), t.levels[k]);
            exr.push_back(out.string());
        }
    }
    nlohmann::json j{{"path", path}, {"textures", list}, {"bytes", total}};
    if (!exrDir.empty()) j["exr"] = exr;
    return j;
}

} // namespace specula::cook
