#include "components/reflection_probe/shader_variants.h"
#include "support/embedded_shader_check.h"

#include <gtest/gtest.h>

namespace specula {
namespace {

// The stores register the probe's GLSL when their variants are created; every file under
// components/ must then be found in memory exactly as it is on disk.
TEST(ProbeShaderFiles, EveryComponentShaderIsCompiledInVerbatim) {
    gpu::addShaderFiles(gpu::embedded::probeShaderFiles());
    EXPECT_GE(test::expectFolderEmbedded(SPECULA_SOURCE_DIR, "components"), 30);
}

} // namespace
} // namespace specula
