#pragma once
// Checks that every GLSL file under a source folder is compiled in (engine/gpu/shader_files.h)
// byte for byte: a table that missed a file or went stale fails here, not in a host's build.
#include "engine/gpu/shader_files.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace specula::test {

inline bool isShaderFile(const std::filesystem::path& p) {
    const std::string name = p.filename().string();
    const auto endsWith = [&](const char* suffix) {
        const std::string s(suffix);
        return name.size() > s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0;
    };
    return endsWith(".glsl") || endsWith(".glsl.h") || endsWith(".vert") || endsWith(".frag") ||
           endsWith(".comp");
}

// Returns how many files were compared.
inline int expectFolderEmbedded(const std::string& sourceRoot, const std::string& folder) {
    namespace fs = std::filesystem;
    int compared = 0;
    for (const auto& entry : fs::recursive_directory_iterator(fs::path(sourceRoot) / folder)) {
        if (!entry.is_regular_file() || !isShaderFile(entry.path())) continue;
        const std::string rel = fs::relative(entry.path(), sourceRoot).generic_string();
        std::ifstream in(entry.path(), std::ios::binary);
        std::ostringstream disk;
        disk << in.rdbuf();
        const auto embedded = gpu::embeddedShaderFile(rel);
        if (!embedded) {
            ADD_FAILURE() << rel << " is not embedded";
            continue;
        }
        EXPECT_EQ(std::string(*embedded), disk.str()) << rel << " differs from its embedded copy";
        ++compared;
    }
    return compared;
}

} // namespace specula::test
