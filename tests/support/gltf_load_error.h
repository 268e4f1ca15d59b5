#pragma once
// Bad glTF input: loadGltf refuses it with one line naming the file and the fault, and adds
// nothing to the registry.
#include "engine/core/error.h"
#include "engine/ecs/registry.h"
#include "engine/scene/gltf_loader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace specula::test {

// Expects loadGltf(path) to throw specula::Error naming the file and containing `fragment`,
// and to leave the registry untouched.
inline void expectLoadError(const std::filesystem::path& path, const std::string& fragment) {
    ecs::Registry reg;
    try {
        loadGltf(path.string(), reg);
        ADD_FAILURE() << path << " loaded; expected an error containing '" << fragment << "'";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(fragment), std::string::npos) << what;
        EXPECT_NE(what.find(path.filename().string()), std::string::npos) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << "not one line: " << what;
    }
    EXPECT_EQ(reg.alive(), 0u);
}

} // namespace specula::test
