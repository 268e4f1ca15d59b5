#include "engine/gpu/shader_files.h"

#include <filesystem>
#include <map>
#include <mutex>
#include <string>

namespace specula::gpu {

namespace {

struct Registry {
    std::mutex mutex;
    std::map<std::string, std::string_view, std::less<>> files;
    bool engineAdded = false;
};

Registry& registry() {
    static Registry r;
    return r;
}

std::string normalised(std::string_view path) {
    return std::filesystem::path(path).lexically_normal().generic_string();
}

void addLocked(Registry& r, std::span<const ShaderFile> files) {
    for (const ShaderFile& f : files)
        r.files.insert_or_assign(normalised(f.path), f.text);
}

} // namespace

void addShaderFiles(std::span<const ShaderFile> files) {
    Registry& r = registry();
    std::lock_guard lock(r.mutex);
    addLocked(r, files);
}

std::optional<std::string_view> embeddedShaderFile(std::string_view path) {
    Registry& r = registry();
    std::lock_guard lock(r.mutex);
    if (!r.engineAdded) {
        addLocked(r, embedded::engineShaderFiles());
        r.engineAdded = true;
    }
    const auto it = r.files.find(normalised(path));
    if (it == r.files.end()) return std::nullopt;
    return it->second;
}

} // namespace specula::gpu
