#pragma once
// One headless context per test suite: context creation costs more than most GPU tests.
#include "engine/context/context.h"

#include <gtest/gtest.h>

#include <memory>

namespace specula::test {

class GlTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        if (!context()) context() = gpu::GlContext::createHeadless();
    }
    static void TearDownTestSuite() { context().reset(); }
    void SetUp() override { context()->makeCurrent(); }

    static std::unique_ptr<gpu::GlContext>& context() {
        static std::unique_ptr<gpu::GlContext> c;
        return c;
    }
};

} // namespace specula::test
