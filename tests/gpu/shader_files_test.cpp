#include "engine/core/error.h"
#include "engine/gpu/shader.h"
#include "engine/gpu/shader_files.h"
#include "support/embedded_shader_check.h"

#include <gtest/gtest.h>

namespace specula::gpu {
namespace {

TEST(ShaderFiles, EveryEngineShaderIsCompiledInVerbatim) {
    EXPECT_GE(test::expectFolderEmbedded(SPECULA_SOURCE_DIR, "engine"), 8);
}

TEST(ShaderFiles, PathsAreNormalised) {
    const auto plain = embeddedShaderFile("engine/render/shaders/scene.vert");
    const auto dotted = embeddedShaderFile("engine/./render/shaders/../shaders/scene.vert");
    ASSERT_TRUE(plain && dotted);
    EXPECT_EQ(plain->data(), dotted->data());
    EXPECT_FALSE(embeddedShaderFile("engine/render/shaders/no_such.vert"));
}

// A registered file is read from its table, not from the disk: these paths exist only in
// memory, and the include resolves against the table too.
TEST(ShaderFiles, ProgramsExpandFromRegisteredTextWithoutTheDisk) {
    static const ShaderFile files[] = {
        {"memory_only/main.frag", "#include \"memory_only/colour.glsl\"\nvoid main() {}\n"},
        {"memory_only/colour.glsl", "const vec3 kColour = vec3(1.0);\n"},
    };
    addShaderFiles(files);
    const ExpandedSource ex = expandShader(ShaderSource::file("memory_only/main.frag"), {});
    EXPECT_NE(ex.text.find("const vec3 kColour = vec3(1.0);"), std::string::npos) << ex.text;
    ASSERT_EQ(ex.files.size(), 3u);
    EXPECT_EQ(ex.files[2], "memory_only/colour.glsl");
}

TEST(ShaderFiles, AFileNeitherEmbeddedNorOnDiskNamesWhereItLooked) {
    try {
        expandShader(ShaderSource::file("memory_only/missing.frag"), {});
        FAIL() << "expected an error";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("not embedded"), std::string::npos) << what;
        EXPECT_NE(what.find("memory_only/missing.frag"), std::string::npos) << what;
    }
}

} // namespace
} // namespace specula::gpu
