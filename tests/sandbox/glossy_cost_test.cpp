// The cost columns of specula-sandbox glossy (sandbox/lib/bench/glossy_timing.h), in-process on the
// room at a small size: the memory column against texture sizes worked out here from the
// formats (RGBA32F cube faces and sky, the light field's RGBA8 atlas) and against the probe
// stores' own count after the timed runs; a pass ratio exactly for the methods with a shader.
// No assertion on a time: llvmpipe's figures mean nothing absolute.
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "sandbox/lib/bench/glossy_bench.h"
#include "sandbox/lib/bench/glossy_timing.h"
#include "sandbox/lib/render/reflection_scene.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;
using namespace specula;
using namespace specula::sandbox;

namespace {

struct Scratch {
    fs::path dir =
        fs::temp_directory_path() / ("specula-glossy-cost-" + std::to_string(::getpid()));
    Scratch() { fs::remove_all(dir); }
    ~Scratch() { fs::remove_all(dir); }
};

constexpr double kMiB = 1024.0 * 1024.0;

} // namespace

TEST(GlossyCost, MemoryIsTheTexturesTheStoresHoldAndOnlyShadedMethodsAreTimed) {
    Scratch scratch;
    GlossyBenchOptions o;
    o.scene = defaultScenePath();
    o.sky = defaultSkyPath();
    o.out = scratch.dir.string();
    o.roughness = {0.f, 0.3f};
    o.width = 48;
    o.height = 36;
    o.faceRes = 16;
    o.samples = 4;
    o.progress = false;
    o.timingRounds = 2;
    std::ostringstream log;
    const GlossyBenchResult r = runGlossyBench(o, log);
    SCOPED_TRACE(log.str());

    // The stores count what they uploaded: four distance probes (one layered) and the light
    // field.
    EXPECT_GT(r.storeBytes, 0u);
    EXPECT_EQ(r.storeBytes, r.expectedStoreBytes);
    EXPECT_GT(r.envmapMs, 0.0);
    EXPECT_FALSE(r.timer.empty());

    // Mirror rows from the formats: the composite cube, 6 faces of 16^2 RGBA32F, and the sky
    // panorama in RGBA32F; the light field, 6 slabs of (8 x 64)^2 RGBA8 (the bench's 8 x 8
    // cameras of 64^2).
    const ReflectionScene scene(o.scene, o.sky);
    const double distanceMirror =
        (6.0 * 16 * 16 * 16 + double(scene.sky().width) * scene.sky().height * 16) / kMiB;
    const double lightFieldMirror = 6.0 * 512 * 512 * 4 / kMiB;
    const double objectLayers = double(
        readDistanceProbe((scratch.dir / "probes/distance/manifest.json").string()).layers.size() -
        1);
    ASSERT_GT(objectLayers, 0.0);
    const std::vector<std::string>& methods = glossyBenchMethods();
    ASSERT_EQ(r.rows.size(), 2 * methods.size());
    for (std::size_t m = 0; m < methods.size(); ++m) {
        const GlossyBenchRow& mirror = r.rows[m];
        const GlossyBenchRow& rough = r.rows[methods.size() + m];
        ASSERT_EQ(mirror.method, methods[m]);
        const bool lightField = GlossyBenchMethod(m) == GlossyBenchMethod::LightField;
        if (GlossyBenchMethod(m) == GlossyBenchMethod::LayeredFootprint) {
            // The object layers' tiles on top: something, yet less than whole RGBA32F cubes
            // of 16^2 faces for each of the room's object layers.
            EXPECT_GT(mirror.memoryMiB, distanceMirror) << methods[m];
            EXPECT_LT(mirror.memoryMiB - distanceMirror, objectLayers * 6.0 * 16 * 16 * 16 / kMiB)
                << methods[m];
        } else {
            EXPECT_NEAR(mirror.memoryMiB, lightField ? lightFieldMirror : distanceMirror, 1e-9)
                << methods[m];
        }
        // Roughness adds the chain (or the mips) and the 32 x 32 R32F albedo table.
        EXPECT_GE(rough.memoryMiB - mirror.memoryMiB, (32.0 * 32 * 4 + 1) / kMiB) << methods[m];
        for (const GlossyBenchRow* row : {&mirror, &rough}) {
            if (hasGpuPath(GlossyBenchMethod(m))) {
                EXPECT_TRUE(std::isfinite(row->ratioToEnvmap) && row->ratioToEnvmap > 0.0)
                    << methods[m] << " " << row->ratioToEnvmap;
            } else {
                EXPECT_LT(row->ratioToEnvmap, 0.0) << methods[m];
            }
        }
    }
    EXPECT_FALSE(hasGpuPath(GlossyBenchMethod::RectifiedRoughnessLevel));

    // The CSV carries both columns; the CPU-only method's ratio is "none".
    std::ifstream csv(scratch.dir / "glossy.csv");
    std::string header, line;
    std::getline(csv, header);
    EXPECT_EQ(header, "roughness,method,psnr,noise_floor_psnr,ratio_to_envmap,memory_mib");
    int none = 0, rows = 0;
    while (std::getline(csv, line)) {
        ++rows;
        if (line.find("\"rectified (roughness level)\"") != std::string::npos)
            none += line.find(",none,") != std::string::npos;
    }
    EXPECT_EQ(rows, int(r.rows.size()));
    EXPECT_EQ(none, 2);
}

TEST(GlossyCost, WithoutTimingEveryRatioIsNoneAndMemoryStays) {
    Scratch scratch;
    GlossyBenchOptions o;
    o.scene = defaultScenePath();
    o.sky = "";
    o.out = scratch.dir.string();
    o.roughness = {0.2f};
    o.width = 32;
    o.height = 24;
    o.faceRes = 8;
    o.samples = 2;
    o.progress = false;
    o.timing = false;
    std::ostringstream log;
    const GlossyBenchResult r = runGlossyBench(o, log);
    EXPECT_EQ(r.envmapMs, 0.0);
    for (const GlossyBenchRow& row : r.rows) {
        EXPECT_LT(row.ratioToEnvmap, 0.0) << row.method;
        EXPECT_GT(row.memoryMiB, 0.0) << row.method;
    }
}
