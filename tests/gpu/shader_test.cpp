#include "engine/core/error.h"
#include "engine/gpu/render_target.h"
#include "engine/gpu/shader.h"
#include "gl_test_context.h"

#include <string_view>

namespace specula::gpu {
namespace {

// gtest only (the test target does not link gmock).
::testing::AssertionResult HasSubstr(std::string_view text, std::string_view part) {
    if (text.find(part) != std::string_view::npos) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "\"" << part << "\" not in:\n" << text;
}
using ShaderTest = test::GlTest;

ShaderSource file(const char* p) {
    return ShaderSource::file(p);
}

glm::vec4 drawFullscreen(Program& program) {
    RenderTarget target(4, 4);
    target.bind();
    target.clear();
    VertexArray vao = VertexArray::create();
    program.setUniform("uRect", glm::vec4(-1.f, -1.f, 1.f, 1.f));
    program.use();
    glBindVertexArray(vao.id());
    glDrawArrays(GL_TRIANGLES, 0, 6);
    return target.readback().rgba(1, 1);
}

TEST_F(ShaderTest, ErrorInIncludedFileNamesThatFileAndLine) {
    try {
        buildProgram(file("tests/gpu/shaders/rect.vert"),
                     file("tests/gpu/shaders/broken_main.frag"));
        FAIL() << "expected a compile error";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), "tests/gpu/shaders/broken_include.glsl") << e.what();
        EXPECT_EQ(e.field(), "line 5") << e.what();
        EXPECT_TRUE(HasSubstr(e.what(), "tests/gpu/shaders/broken_include.glsl:5"));
        EXPECT_TRUE(HasSubstr(e.what(), "fragment"));
    }
}

TEST_F(ShaderTest, LineNumbersResumeAfterAnInclude) {
    try {
        buildProgram(file("tests/gpu/shaders/rect.vert"),
                     file("tests/gpu/shaders/error_after_include.frag"), {"SOME_DEFINE"});
        FAIL() << "expected a compile error";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), "tests/gpu/shaders/error_after_include.frag") << e.what();
        EXPECT_EQ(e.field(), "line 8") << e.what();
        EXPECT_TRUE(HasSubstr(e.what(), "SOME_DEFINE"));
    }
}

TEST_F(ShaderTest, EachFileIsIncludedOnceEvenInACycle) {
    Program p =
        buildProgram(file("tests/gpu/shaders/rect.vert"), file("tests/gpu/shaders/includes.frag"));
    const glm::vec4 c = drawFullscreen(p);
    EXPECT_FLOAT_EQ(c.r, 0.5f);
}

TEST_F(ShaderTest, MissingIncludeNamesTheIncludingFile) {
    try {
        buildProgram(file("tests/gpu/shaders/rect.vert"),
                     file("tests/gpu/shaders/missing_include.frag"));
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), "tests/gpu/shaders/missing_include.frag");
        EXPECT_EQ(e.field(), "line 2");
        EXPECT_TRUE(HasSubstr(e.what(), "does_not_exist.glsl"));
    }
}

TEST_F(ShaderTest, MissingStageFileIsAnError) {
    EXPECT_THROW(
        buildProgram(file("tests/gpu/shaders/nope.vert"), file("tests/gpu/shaders/solid.frag")),
        Error);
}

TEST_F(ShaderTest, LinkErrorIsReported) {
    try {
        buildProgram(file("tests/gpu/shaders/link_mismatch.vert"),
                     file("tests/gpu/shaders/link_mismatch.frag"));
        FAIL() << "expected a link error";
    } catch (const Error& e) {
        EXPECT_EQ(e.field(), "link") << e.what();
        EXPECT_TRUE(HasSubstr(e.file(), "link_mismatch.vert"));
    }
}

TEST_F(ShaderTest, DefinePermutationsChangeTheOutput) {
    Program green =
        buildProgram(file("tests/gpu/shaders/rect.vert"), file("tests/gpu/shaders/permute.frag"));
    Program red = buildProgram(file("tests/gpu/shaders/rect.vert"),
                               file("tests/gpu/shaders/permute.frag"), {"RED", "BLUE_LEVEL=0.25"});
    EXPECT_EQ(drawFullscreen(green), glm::vec4(0.f, 1.f, 0.f, 1.f));
    EXPECT_EQ(drawFullscreen(red), glm::vec4(1.f, 0.f, 0.25f, 1.f));
}

TEST_F(ShaderTest, AbsolutePathsAndTextSourcesWork) {
    const auto abs = shaderRoot() / "tests/gpu/shaders/rect.vert";
    Program p = buildProgram(
        ShaderSource::file(abs),
        ShaderSource::text("inline.frag", "#include \"tests/gpu/shaders/solid.frag\"\n"));
    p.setUniform("uColor", glm::vec4(0.125f, 0.25f, 0.5f, 1.f));
    EXPECT_EQ(drawFullscreen(p), glm::vec4(0.125f, 0.25f, 0.5f, 1.f));
}

// The log formats of drivers this machine does not have, checked on synthetic logs.
TEST(ShaderLog, RewritesMesaNvidiaAndGlslangFormats) {
    const std::vector<std::string> files = {"<preamble>", "a.frag", "inc/b.glsl"};
    std::string file;
    int line = 0;
    std::string out = rewriteShaderLog("1:3(10): warning: unused\n2:12(5): error: `x' undeclared\n",
                                       files, &file, &line);
    EXPECT_EQ(file, "inc/b.glsl");
    EXPECT_EQ(line, 12);
    EXPECT_TRUE(HasSubstr(out, "a.frag:3:10: warning: unused"));
    EXPECT_TRUE(HasSubstr(out, "inc/b.glsl:12:5: error: `x' undeclared"));

    file.clear();
    out = rewriteShaderLog("1(7) : error C1008: undefined variable \"x\"\n", files, &file, &line);
    EXPECT_EQ(file, "a.frag");
    EXPECT_EQ(line, 7);
    EXPECT_TRUE(HasSubstr(out, "a.frag:7: error C1008"));

    // Mesa reports source 0 for everything: the file index rides in the line number.
    file.clear();
    out = rewriteShaderLog("0:200012(3): error: bad\n", files, &file, &line);
    EXPECT_EQ(file, "inc/b.glsl");
    EXPECT_EQ(line, 12);
    EXPECT_TRUE(HasSubstr(out, "inc/b.glsl:12:3: error: bad"));

    file.clear();
    out = rewriteShaderLog("ERROR: 2:4: 'foo' : undeclared identifier\n", files, &file, &line);
    EXPECT_EQ(file, "inc/b.glsl");
    EXPECT_EQ(line, 4);
}

TEST(ShaderExpand, PreambleDefinesAndLineDirectives) {
    const ExpandedSource ex =
        expandShader(ShaderSource::text(
                         "t.frag", "#version 330\n#include \"tests/gpu/shaders/solid.frag\"\nx\n"),
                     {"A", "B=2"});
    EXPECT_EQ(ex.text.rfind("#version 450 core\n#define A\n#define B 2\n#line 100001 1\n", 0), 0u)
        << ex.text;
    EXPECT_EQ(ex.files,
              (std::vector<std::string>{"<preamble>", "t.frag", "tests/gpu/shaders/solid.frag"}));
    EXPECT_TRUE(HasSubstr(ex.text, "#line 200001 2\n"));
    EXPECT_TRUE(HasSubstr(ex.text, "#line 100003 1\nx\n"));
    EXPECT_EQ(ex.text.find("#version 330"), std::string::npos);
}

} // namespace
} // namespace specula::gpu
