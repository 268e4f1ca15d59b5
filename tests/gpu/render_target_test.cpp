#include "engine/core/error.h"
#include "engine/gpu/render_target.h"
#include "engine/gpu/shader.h"
#include "gl_test_context.h"

namespace specula::gpu {
namespace {

using RenderTargetTest = test::GlTest;

TEST_F(RenderTargetTest, ClearColourReadsBackExactly) {
    RenderTarget target(7, 5); // odd sizes catch row-stride mistakes
    EXPECT_EQ(target.size(), glm::ivec2(7, 5));
    // Values no 8-bit or half-float path would keep: proves the target is full float.
    const glm::vec4 c(0.123456f, 3.5f, -0.25f, 1e-5f);
    target.clear(c);
    const Image img = target.readback();
    ASSERT_EQ(img.width, 7);
    ASSERT_EQ(img.height, 5);
    ASSERT_EQ(img.channels, 4);
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 7; ++x)
            ASSERT_EQ(img.rgba(x, y), c) << x << "," << y;
    const Image depth = target.readbackDepth();
    EXPECT_EQ(depth.rgba(3, 2).r, 1.f);
}

TEST_F(RenderTargetTest, RowZeroIsTheTopOfThePicture) {
    RenderTarget target(8, 6);
    target.bind();
    target.clear(glm::vec4(0.f, 0.f, 0.f, 1.f));
    Program p = buildProgram(ShaderSource::file("tests/gpu/shaders/rect.vert"),
                             ShaderSource::file("tests/gpu/shaders/solid.frag"));
    p.setUniform("uRect", glm::vec4(-1.f, 0.f, 1.f, 1.f)); // NDC y > 0: the upper half
    p.setUniform("uColor", glm::vec4(1.f, 0.5f, 0.25f, 1.f));
    VertexArray vao = VertexArray::create();
    p.use();
    glBindVertexArray(vao.id());
    glDisable(GL_DEPTH_TEST);
    glDrawArrays(GL_TRIANGLES, 0, 6);
    const Image img = target.readback();
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 8; ++x) {
            const glm::vec4 expected =
                y < 3 ? glm::vec4(1.f, 0.5f, 0.25f, 1.f) : glm::vec4(0.f, 0.f, 0.f, 1.f);
            ASSERT_EQ(img.rgba(x, y), expected) << x << "," << y;
        }
}

TEST_F(RenderTargetTest, RejectsEmptySize) {
    EXPECT_THROW(RenderTarget(0, 4), Error);
}

TEST_F(RenderTargetTest, WrappersAreMoveOnlyOwners) {
    Buffer a = Buffer::create(nullptr, 16);
    const GLuint id = a.id();
    ASSERT_NE(id, 0u);
    Buffer b = std::move(a);
    EXPECT_EQ(a.id(), 0u);
    EXPECT_EQ(b.id(), id);
    EXPECT_TRUE(glIsBuffer(id));
    b.reset();
    EXPECT_FALSE(glIsBuffer(id));
}

} // namespace
} // namespace specula::gpu
