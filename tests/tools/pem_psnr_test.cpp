// The PEM bake's own fit report never prints a number it did not measure (issue 34): a
// sky-only scene without a sky is black against black (it scored 120 dB), and one sample
// along the open camera path has nothing half-way (it printed "nan dB"). Both say "none", as
// every PSNR of the tools does (formatPsnr); a measured fit still prints its dB.
#include "assetcooker/lib/flavours/pem/pem_samples.h"
#include "support/shell_tool.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

namespace fs = std::filesystem;

namespace {

const fs::path kCook = fs::path(SPECULA_BIN_DIR) / "specula-cook";
const std::string kAssets = std::string(SPECULA_SOURCE_DIR) + "/assets/";

using specula::test::shellQuote;
using specula::test::TempDir;
using specula::test::ToolRun;

// The "fit against the ray tracer" line of a PEM bake of `scene` with `flags`.
std::string fitLine(const std::string& scene, const std::string& flags) {
    const TempDir dir("pem-psnr");
    const ToolRun r = specula::test::runShellTool(
        kCook, "bake " + shellQuote(kAssets + scene) +
                   " --flavour pem --samples 1 --face-res 8 --image-size 64x48 " + flags +
                   " --out " + shellQuote((dir.path / "pem").string()));
    EXPECT_EQ(r.status, 0) << r.err;
    const std::size_t at = r.out.find("fit against the ray tracer");
    if (at == std::string::npos) return "(no fit line) " + r.out;
    return r.out.substr(at, r.out.find('\n', at) - at);
}

} // namespace

TEST(PemPsnr, BlackAgainstBlackIsNoPsnr) {
    const std::string line = fitLine("sky_only/sky_only.gltf", "--sky ''");
    EXPECT_NE(line.find("on the samples none dB"), std::string::npos) << line;
    EXPECT_EQ(line.find("120"), std::string::npos) << line;
}

TEST(PemPsnr, NothingHalfWayIsNoneNotNan) {
    const std::string line = fitLine("room/room_camera_path.gltf", "--path camera");
    EXPECT_NE(line.find("half-way between them none dB (worst none)"), std::string::npos) << line;
    EXPECT_EQ(line.find("nan"), std::string::npos) << line;
    // The sample itself was measured: a number of dB.
    EXPECT_EQ(line.find("on the samples none"), std::string::npos) << line;
}

TEST(PemPsnr, SamplesPsnrIsNanOnlyWhenNothingIsMeasured) {
    using specula::PemSample;
    using specula::PemSamples;
    const auto black = [](const PemSample&) { return glm::vec3(0.f); };
    EXPECT_TRUE(std::isnan(specula::pemSamplesPsnr(PemSamples{}, black)));
    PemSamples dark(3);
    EXPECT_TRUE(std::isnan(specula::pemSamplesPsnr(dark, black))) << "black against black";
    // A black map against a lit target is a real (bad) score, an exact match 120 dB.
    PemSamples lit(3);
    for (PemSample& s : lit)
        s.target = glm::vec3(0.5f);
    EXPECT_NEAR(specula::pemSamplesPsnr(lit, black), 20.0 * std::log10(2.0), 1e-6);
    EXPECT_NEAR(specula::pemSamplesPsnr(lit, [](const PemSample&) { return glm::vec3(0.5f); }),
                120.0, 1e-9);
}
