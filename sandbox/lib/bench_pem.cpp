#include "components/reflection_probe/pem/pem_probe.h"
#include "components/reflection_probe/pem/pem_probe_cpu.h"
#include "engine/core/error.h"
#include "engine/image/compare.h"
#include "sandbox/lib/bench_internal.h"
#include "sandbox/lib/probe_source.h"

#include <cstdio>
#include <filesystem>

namespace fs = std::filesystem;

namespace specula {

namespace {

// Mean over the samples of what the cooker measured: on the viewpoints and half-way between.
void logCookerFit(std::ostream& log, const std::string& sceneName, int samples,
                  const CookResult& cooked) {
    double on = 0, off = 0, infer = 0;
    for (const PemSampleFit& f : cooked.pemFits)
        on += f.psnrOn, off += f.psnrOff, infer += f.inferSeconds;
    const double n = double(std::max<std::size_t>(cooked.pemFits.size(), 1));
    char line[256];
    std::snprintf(line, sizeof line,
                  "%s: PEM N=%d baked in %.1f s; the cooker's fit on the reflector rays: %.1f dB "
                  "on, %.1f dB half-way; inference %.2f s per sample\n",
                  sceneName.c_str(), samples, cooked.bakeSeconds, on / n, off / n, infer / n);
    log << line << std::flush;
}

// Texture fetches per reflector pixel of the blend at `probe`, counted by the CPU twin on the
// camera's reflector rays as Embree finds them (the shader's inputs up to normal
// interpolation): a distance-geometry lookup reads the distance cube while it searches.
double pemFetchesPerPixel(ProbeScene& scene, const CameraView& cam, const PemAsset& asset,
                          const PemProbe& probe) {
    const PemSamples rays = tracePemSamples(scene, cam, asset.centre, {});
    const glsl::PemParams p = pemParams(asset, probe);
    const PemLookupCpu a(asset.samples[std::size_t(p.layerA / 6)].map);
    const PemLookupCpu b(asset.samples[std::size_t(p.layerB / 6)].map);
    double sum = 0;
    for (const PemSample& r : rays)
        sum += a.textureFetches(r.x, r.l) + (p.wb > 0.f ? b.textureFetches(r.x, r.l) : 0);
    return sum / double(rays.size());
}

} // namespace

void appendPemRows(ReflectionScene& scene, FrameRenderer& fr, const std::string& sceneName,
                   const std::string& outDir, const PemBenchSweep& sweep, BenchFrameBudget budget,
                   double envmapMs, BenchReport& report, PlotPanel& panel, std::ostream& log) {
    for (const int samples : sweep.samples) {
        const PemCookSettings settings =
            sandboxPemSettings({sweep.faceRes, sweep.width, sweep.height}, samples);
        log << sceneName << ": baking the PEM (" << samples << " viewpoints, " << settings.faceRes
            << "^2 faces, inferred for " << sweep.width << "x" << sweep.height << ")\n"
            << std::flush;
        CookResult cooked;
        try {
            cooked = cookSceneInto(
                scene,
                (fs::path(outDir) / "probes" / (sceneName + "_pem" + std::to_string(samples)))
                    .string(),
                settings, false, &log);
        } catch (const Error& e) {
            log << sceneName << ": no PEM rows (" << e.what() << ")\n";
            return;
        }
        logCookerFit(log, sceneName, samples, cooked);
        struct Viewpoint {
            const char* where;
            float t;
        };
        // At the first sample, and half-way between the first two (where the blend is
        // furthest from both maps it blends).
        const float half = 0.5f / float(samples);
        for (const Viewpoint& v : {Viewpoint{"on", 0.f}, Viewpoint{"off", half}}) {
            const CameraView cam =
                walkOrbitCameraView(scene.probeScene(), sweep.width, sweep.height, v.t);
            BenchTruth truth{scene.groundTruth(cam, true), scene.groundTruth(cam, false), Image{}};
            truth.mask = erodedMask(truth.env.mirrorMask);
            PemProbe probe;
            probe.parameter = v.t;
            scene.setProbe(cooked.manifest, probe);
            fr.probes().sync(scene.registry());
            BenchRow row;
            row.scene = sceneName;
            row.method = kPemMethods[0].label.name;
            row.params = "N=" + std::to_string(samples) + " t=" + v.where;
            measureProbeRow(fr, cam, truth, budget, row);
            row.bakeSeconds = cooked.bakeSeconds;
            row.fetchesPerPixel = pemFetchesPerPixel(scene.probeScene(), cam,
                                                     std::get<PemAsset>(cooked.asset), probe);
            row.ratioToEnvmap = row.msMedian / envmapMs;
            logBenchRow(log, row);
            panel.points.push_back({row.method, row.params, row.ratioToEnvmap, row.psnr});
            report.rows.push_back(row);
        }
    }
}

} // namespace specula
