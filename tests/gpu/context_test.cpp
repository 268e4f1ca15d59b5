#include "engine/context/context.h"
#include "engine/core/error.h"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <cstdlib>

namespace specula::gpu {
namespace {

TEST(GlContext, HeadlessIsCoreAtLeast45AndNamesItsRenderer) {
    auto ctx = GlContext::createHeadless();
    ASSERT_TRUE(ctx);
    EXPECT_TRUE(ctx->isHeadless());
    EXPECT_FALSE(ctx->renderer().empty());
    EXPECT_FALSE(ctx->version().empty());
    EXPECT_GE(ctx->majorVersion() * 10 + ctx->minorVersion(), 45) << ctx->version();
    GLint profile = 0;
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    std::printf("renderer: %s\nversion: %s\nvia: %s\n", ctx->renderer().c_str(),
                ctx->version().c_str(), ctx->origin().c_str());
}

TEST(GlContext, TwoHeadlessContextsCoexist) {
    auto a = GlContext::createHeadless();
    auto b = GlContext::createHeadless();
    b.reset(); // must not terminate the display `a` still uses
    a->makeCurrent();
    EXPECT_NE(glGetString(GL_RENDERER), nullptr);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST(GlContext, WindowUnderX) {
    if (!std::getenv("DISPLAY")) GTEST_SKIP() << "no DISPLAY (run under xvfb-run to test)";
    auto ctx = GlContext::createWindow(64, 48, "specula test");
    ASSERT_TRUE(ctx);
    EXPECT_FALSE(ctx->isHeadless());
    EXPECT_NE(ctx->window(), nullptr);
    EXPECT_GE(ctx->majorVersion() * 10 + ctx->minorVersion(), 45) << ctx->version();
    ctx->swapBuffers();
}

} // namespace
} // namespace specula::gpu
