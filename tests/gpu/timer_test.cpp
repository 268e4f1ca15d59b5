#include "engine/gpu/render_target.h"
#include "engine/gpu/shader.h"
#include "engine/gpu/timer.h"
#include "gl_test_context.h"

#include <cmath>

namespace specula::gpu {
namespace {

using TimerTest = test::GlTest;

TEST_F(TimerTest, TimesADrawInFinitePositiveMilliseconds) {
    RenderTarget target(256, 256);
    target.bind();
    Program p = buildProgram(ShaderSource::file("tests/gpu/shaders/rect.vert"),
                             ShaderSource::file("tests/gpu/shaders/solid.frag"));
    p.setUniform("uRect", glm::vec4(-1.f, -1.f, 1.f, 1.f));
    p.setUniform("uColor", glm::vec4(1.f));
    VertexArray vao = VertexArray::create();
    GpuTimer timer;
    auto pass = [&] {
        p.use();
        glBindVertexArray(vao.id());
        for (int i = 0; i < 20; ++i)
            glDrawArrays(GL_TRIANGLES, 0, 6);
    };
    // llvmpipe's first draw-covering query in a context is garbage, which the timer must
    // reject (NaN) rather than pass on as a huge time.
    const double warmUp = timer.measure(pass);
    EXPECT_TRUE(std::isnan(warmUp) || (warmUp > 0.0 && warmUp < 10000.0)) << warmUp;
    const double ms = timer.measure(pass);
    EXPECT_TRUE(std::isfinite(ms));
    EXPECT_GT(ms, 0.0);
    EXPECT_LT(ms, 10000.0);
}

TEST(MedianMs, OddEvenAndEmpty) {
    EXPECT_DOUBLE_EQ(medianMs({3.0, 1.0, 2.0}), 2.0);
    EXPECT_DOUBLE_EQ(medianMs({4.0, 1.0, 3.0, 2.0}), 2.5);
    EXPECT_DOUBLE_EQ(medianMs({5.0}), 5.0);
    EXPECT_TRUE(std::isnan(medianMs({})));
    EXPECT_DOUBLE_EQ(medianMs({1.0, std::nan(""), 3.0}), 2.0);
}

TEST(QuartilesMs, InterpolatedOrderStatisticsWithTheMedianInTheMiddle) {
    // 1..9: positions 2 and 6 of 0..8.
    const Quartiles q = quartilesMs({9.0, 1.0, 8.0, 2.0, 7.0, 3.0, 6.0, 4.0, 5.0});
    EXPECT_DOUBLE_EQ(q.q1, 3.0);
    EXPECT_DOUBLE_EQ(q.median, 5.0);
    EXPECT_DOUBLE_EQ(q.q3, 7.0);
    EXPECT_DOUBLE_EQ(q.iqr(), 4.0);
    // 1..4: positions 0.75, 1.5, 2.25; the median is medianMs's.
    const Quartiles even = quartilesMs({4.0, 2.0, std::nan(""), 1.0, 3.0});
    EXPECT_DOUBLE_EQ(even.q1, 1.75);
    EXPECT_DOUBLE_EQ(even.median, medianMs({1.0, 2.0, 3.0, 4.0}));
    EXPECT_DOUBLE_EQ(even.q3, 3.25);
    EXPECT_TRUE(std::isnan(quartilesMs({std::nan("")}).median));
}

} // namespace
} // namespace specula::gpu
