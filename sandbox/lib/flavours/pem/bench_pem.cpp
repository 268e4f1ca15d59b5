#include "components/reflection_probe/pem/pem_probe.h"
#include "components/reflection_probe/pem/pem_probe_cpu.h"
#include "engine/core/error.h"
#include "engine/image_io/compare.h"
#include "engine/image_io/contact_sheet.h"
#include "engine/image_io/image_io.h"
#include "sandbox/lib/bench/bench_internal.h"
#include "sandbox/lib/walk/probe_source.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <unordered_map>

namespace fs = std::filesystem;

namespace specula {

namespace {

// Mean over the samples of what the cooker measured: on the viewpoints and half-way between.
void logCookerFit(std::ostream& log, const std::string& sceneName, int samples,
                  const CookResult& cooked) {
    // A sample without a PSNR (NaN: nothing measured, or an open path's end) is left out.
    std::vector<double> on, off;
    double infer = 0, self = 0;
    for (const PemSampleFit& f : cooked.pemFits) {
        on.push_back(f.psnrOn), off.push_back(f.psnrOff);
        infer += f.inferSeconds, self += f.selfHitFraction;
    }
    const double n = double(std::max<std::size_t>(cooked.pemFits.size(), 1));
    const PemAsset& asset = std::get<PemAsset>(cooked.asset);
    // Bytes per sample: the distant map, and the local layer's RGBA when there is one.
    const double kib =
        double(PemMap::texelCount(asset.faceRes)) * 12.0 / 1024.0 +
        (asset.localLayer ? double(PemMap::texelCount(asset.localFaceRes)) * 16.0 / 1024.0 : 0.0);
    char line[320];
    std::snprintf(line, sizeof line,
                  "%s: PEM N=%d (%s) baked in %.1f s; the cooker's fit on the reflector rays: "
                  "%s dB on, %s dB half-way; inference %.2f s per sample; %.0f KiB per "
                  "sample (float texels); %.1f%% of rays meet their reflector again\n",
                  sceneName.c_str(), samples, asset.localLayer ? "two layers" : "single map",
                  cooked.bakeSeconds, formatPsnr(meanPsnr(on), 1).c_str(),
                  formatPsnr(meanPsnr(off), 1).c_str(), infer / n, kib, 100.0 * self / n);
    log << line << std::flush;
}

} // namespace

double pemFetchesPerPixel(ProbeScene& scene, const CameraView& cam, const PemAsset& asset,
                          const PemProbe& probe) {
    // With a local layer the hull flags tell which pixels read it (PemSample::onHull).
    std::unordered_map<ecs::Entity, PemHullFlags> hull;
    PemSampleOptions o;
    if (asset.localLayer) {
        for (ecs::Entity e : scene.markup.mirrorEntities)
            if (const Mesh* m = scene.registry.find<Mesh>(e)) hull.emplace(e, pemHullFlags(*m));
        o.layers = true;
        o.hull = &hull;
    }
    const GroundTruthTracer tracer(scene.registry, groundTruthOptions(scene, false));
    const PemSamples rays = tracePemSamples(tracer, cam, asset.centre, o, scene.path);
    const glsl::PemParams p = pemParams(asset, probe);
    const PemLookupCpu a(asset.samples[std::size_t(p.layerA / 6)].map);
    // The shader blends the two samples' texels as it fetches them (one search, both maps
    // read at the texel it finds): one more filtered read when the second sample counts.
    // The local layer: one filtered read per sample off the hull.
    const int perLayer = p.wb > 0.f ? 2 : 1;
    double sum = 0;
    for (const PemSample& r : rays)
        sum += a.textureFetches(r.x, r.l) + (perLayer - 1) +
               (asset.localLayer && !r.onHull ? perLayer : 0);
    return sum / double(rays.size());
}

namespace {

// outDir/pem_<scene>.png: full truth and PEM on and off the manifold, the PEM's error
// against the full truth below each PEM tile (`heat`: one per tile, empty under a truth).
void writePemPicture(const std::string& outDir, const std::string& sceneName,
                     std::vector<Image> tiles, const std::vector<Image>& heat,
                     std::vector<std::string> labels, int width) {
    const int columns = int(tiles.size());
    for (const Image& h : heat) {
        tiles.push_back(h); // an empty tile leaves its cell blank
        labels.push_back(h.empty() ? "" : "error vs full (red >= 0.25)");
    }
    writeImage((fs::path(outDir) / ("pem_" + sceneName + ".png")).string(),
               contactSheet(tiles, labels, columns, std::min(width, 400)));
}

} // namespace

PemCookSettings pemBenchSettings(const PemBenchSweep& sweep, int samples) {
    SourceBakeSize size{sweep.faceRes, sweep.width, sweep.height};
    size.cameraPath = sweep.cameraPath;
    PemCookSettings s = sandboxPemSettings(size, samples);
    s.supersample = sweep.supersample;
    s.rows = sweep.rows;
    s.nonNegative = sweep.nonNegative;
    s.roundingReach = sweep.roundingReach;
    return s;
}

CameraView pemBenchCamera(const ReflectionScene& scene, const PemBenchSweep& sweep, float t) {
    return sweep.cameraPath ? cameraPathView(scene.probeScene(), sweep.width, sweep.height, t)
                            : walkOrbitCameraView(scene.probeScene(), sweep.width, sweep.height, t);
}

float pemBenchHalfWay(const PemBenchSweep& sweep, int samples) {
    if (!sweep.cameraPath) return 0.5f / float(samples);
    return samples > 1 ? 0.5f / float(samples - 1) : 0.f;
}

void appendPemRows(ReflectionScene& scene, FrameRenderer& fr, const std::string& sceneName,
                   const std::string& outDir, const PemBenchSweep& sweep, BenchFrameBudget budget,
                   double envmapMs, BenchReport& report, PlotPanel& panel, std::ostream& log) {
    // Each N baked as the cooker chooses (local layer "auto"); where that gave a local layer,
    // once more without it, rows "... single" beside the layered ones.
    struct Bake {
        int samples;
        bool single;
    };
    std::vector<Bake> bakes;
    for (const int samples : sweep.samples)
        bakes.push_back({samples, false});
    for (std::size_t b = 0; b < bakes.size(); ++b) {
        const int samples = bakes[b].samples;
        PemCookSettings settings = pemBenchSettings(sweep, samples);
        if (bakes[b].single) settings.localLayer = "off";
        log << sceneName << ": baking the PEM (" << samples << " viewpoints on the "
            << (sweep.cameraPath ? "camera path" : "orbit") << ", " << settings.faceRes
            << "^2 faces, inferred for " << sweep.width << "x" << sweep.height << ")\n"
            << std::flush;
        CookResult cooked;
        try {
            cooked = cookSceneInto(scene,
                                   (fs::path(outDir) / "probes" /
                                    (sceneName + "_pem" + std::to_string(samples) +
                                     (bakes[b].single ? "_single" : "")))
                                       .string(),
                                   settings, false, &log);
        } catch (const Error& e) {
            log << sceneName << ": no PEM rows (" << e.what() << ")\n";
            return;
        }
        logCookerFit(log, sceneName, samples, cooked);
        if (!bakes[b].single && std::get<PemAsset>(cooked.asset).localLayer)
            bakes.push_back({samples, true});
        struct Viewpoint {
            const char* where;
            float t;
        };
        // At the first sample, and half-way between the first two (where the blend is
        // furthest from both maps it blends).
        const float half = pemBenchHalfWay(sweep, samples);
        // The picture of the first PEM of the sweep: full truth and PEM, on and off.
        std::vector<Image> tiles, heat;
        std::vector<std::string> labels;
        const bool picture = samples == sweep.samples.front() && !bakes[b].single;
        for (const Viewpoint& v : {Viewpoint{"on", 0.f}, Viewpoint{"off", half}}) {
            const CameraView cam = pemBenchCamera(scene, sweep, v.t);
            BenchTruth truth{scene.groundTruth(cam, true), scene.groundTruth(cam, false), Image{}};
            truth.mask = erodedMask(truth.env.mirrorMask);
            PemProbe probe;
            probe.parameter = v.t;
            scene.setProbe(cooked.manifest, probe);
            fr.probes().sync(scene.registry());
            BenchRow row;
            row.scene = sceneName;
            row.method = kPemMethods[0].label.name;
            row.params = "N=" + std::to_string(samples) + " t=" + v.where +
                         (bakes[b].single ? " single" : "");
            Image shot = measureProbeRow(fr, cam, truth, budget, row);
            if (picture) {
                labels.push_back(std::string("full truth t=") + v.where);
                labels.push_back(row.method + " " + row.params + " " + formatPsnr(row.psnrFull, 1) +
                                 " dB full");
                heat.push_back(Image{});
                heat.push_back(errorHeatmap(shot, truth.full.color, &truth.mask, 0.25f));
                tiles.push_back(truth.full.color);
                tiles.push_back(std::move(shot));
            }
            row.bakeSeconds = cooked.bakeSeconds;
            row.fetchesPerPixel = pemFetchesPerPixel(scene.probeScene(), cam,
                                                     std::get<PemAsset>(cooked.asset), probe);
            row.ratioToEnvmap = row.msMedian / envmapMs;
            logBenchRow(log, row);
            panel.points.push_back({row.method, row.params, row.ratioToEnvmap, row.psnr});
            report.rows.push_back(row);
            if (!bakes[b].single && (b == 0 || v.t > 0.f) && !sweep.referenceAsset.empty()) {
                // The single-bounce reference from this camera: at the sample (the same
                // camera for every N) once, half-way (pemBenchHalfWay) for each N. Not plotted:
                // the plot's points all see the scene camera.
                scene.setProbe(sweep.referenceAsset, sweep.reference.distance);
                fr.probes().sync(scene.registry());
                BenchRow ref;
                ref.scene = sceneName;
                ref.method = sweep.reference.method;
                ref.params = sweep.reference.params + " pem-camera N=" + std::to_string(samples) +
                             " t=" + v.where;
                measureProbeRow(fr, cam, truth, budget, ref);
                ref.fetchesPerPixel = countFetches(fr, scene, cam, truth.mask);
                ref.ratioToEnvmap = ref.msMedian / envmapMs;
                ref.bakeSeconds = sweep.referenceBakeSeconds;
                logBenchRow(log, ref);
                report.rows.push_back(ref);
            }
        }
        if (picture) writePemPicture(outDir, sceneName, tiles, heat, labels, sweep.width);
        // The MIP comparison once per scene, on the first N's bake as the cooker chose it.
        if (b == 0)
            appendPemMipRows(scene, fr, sceneName, outDir, sweep, samples, cooked, budget, envmapMs,
                             report, panel, log);
    }
}

} // namespace specula
