#include "components/reflection_probe/pem/pem_probe.h"
#include "engine/core/error.h"
#include "engine/image/compare.h"
#include "sandbox/lib/bench_internal.h"
#include "sandbox/lib/probe_source.h"

#include <filesystem>

namespace fs = std::filesystem;

namespace specula {

void appendPemRows(ReflectionScene& scene, FrameRenderer& fr, const std::string& sceneName,
                   const std::string& outDir, int width, int height, BenchFrameBudget budget,
                   double envmapMs, BenchReport& report, PlotPanel& panel, std::ostream& log) {
    const PemCookSettings settings = sandboxPemSettings(64);
    log << sceneName << ": baking the PEM (" << settings.samples << " viewpoints, "
        << settings.faceRes << "^2 faces)\n"
        << std::flush;
    std::string manifest;
    double bakeSeconds = 0;
    try {
        const CookResult cooked =
            cookSceneInto(scene, (fs::path(outDir) / "probes" / (sceneName + "_pem")).string(),
                          settings, false, &log);
        manifest = cooked.manifest;
        bakeSeconds = cooked.bakeSeconds;
    } catch (const Error& e) {
        log << sceneName << ": no PEM rows (" << e.what() << ")\n";
        return;
    }
    struct Viewpoint {
        const char* params;
        float t;
    };
    const float half = 0.5f / float(settings.samples);
    for (const Viewpoint& v : {Viewpoint{"t=on", 0.f}, Viewpoint{"t=off", half}}) {
        const CameraView cam = walkOrbitCameraView(scene.probeScene(), width, height, v.t);
        BenchTruth truth{scene.groundTruth(cam, true), scene.groundTruth(cam, false), Image{}};
        truth.mask = erodedMask(truth.env.mirrorMask);
        PemProbe probe;
        probe.parameter = v.t;
        scene.setProbe(manifest, probe);
        fr.probes().sync(scene.registry());
        BenchRow row;
        row.scene = sceneName;
        row.method = kPemMethods[0].label.name;
        row.params = v.params;
        measureProbeRow(fr, cam, truth, budget, row);
        row.bakeSeconds = bakeSeconds;
        row.fetchesPerPixel = 2; // one bilinear cube lookup in each of the two nearest samples
        row.ratioToEnvmap = row.msMedian / envmapMs;
        logBenchRow(log, row);
        panel.points.push_back({row.method, row.params, row.ratioToEnvmap, row.psnr});
        report.rows.push_back(row);
    }
}

} // namespace specula
