// The storage-format rows of the bench (issue 36, item 4): the scene's probe with its composite
// stored as `--compress bc6h` stores it, drawn on the GPU from its blocks beside the float rows
// of the same run, so PSNR and GPU bytes compare per format on one camera and one truth.
#include "components/reflection_probe/distance/distance_compression.h"
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "components/reflection_probe/distance/writer/distance_probe_writer.h"
#include "engine/core/error.h"
#include "sandbox/lib/bench/bench_internal.h"

#include <chrono>
#include <filesystem>

namespace fs = std::filesystem;

namespace specula {

void appendFormatRows(ReflectionScene& scene, FrameRenderer& fr, const CameraView& cam,
                      const BenchTruth& truth, BenchFrameBudget budget,
                      const std::string& sceneName, const std::string& probeDir,
                      const std::vector<MethodVariant>& variants, double envmapMs,
                      BenchReport& report, std::ostream& log) {
    const auto start = std::chrono::steady_clock::now();
    const std::string dir = probeDir + "_bc6h";
    try {
        DistanceProbeAsset asset =
            readDistanceProbe((fs::path(probeDir) / "manifest.json").string());
        compressComposite(asset);
        writeDistanceProbe(asset, dir, scene.path());
    } catch (const Error& e) {
        log << "  " << sceneName << ": no BC6H rows (" << e.what() << ")\n";
        return;
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    log << sceneName << ": the probe's composite in BC6H (" << seconds << " s)\n";
    const std::string manifest = (fs::path(dir) / "manifest.json").string();
    for (const MethodVariant& v : variants) {
        // Every distance method once: at d_e = 0.01, or its only row.
        if (v.kind != VariantKind::Probe || v.lightField >= 0 || v.planned ||
            (v.params != "-" && v.params != formatTolerance(0.01f)))
            continue;
        BenchRow row;
        row.scene = sceneName;
        row.method = v.method;
        row.params = v.params + " bc6h";
        scene.setProbe(manifest, v.distance);
        if (!syncBenchProbe(fr, scene, row, log)) continue;
        measureProbeRow(fr, cam, truth, budget, row);
        row.bakeSeconds = seconds; // the compression, on top of the float probe's bake
        row.fetchesPerPixel = countFetches(fr, scene, cam, truth.mask);
        row.ratioToEnvmap = row.msMedian / envmapMs;
        logBenchRow(log, row);
        report.rows.push_back(row);
    }
}

} // namespace specula
