#include "sandbox/lib/bench/bench.h"

#include "components/reflection_probe/distance/distance_probe_cpu.h"
#include "components/reflection_probe/distance/system/distance_store.h"
#include "components/reflection_probe/lightfield/lightfield_probe.h"
#include "engine/context/context.h"
#include "engine/core/error.h"
#include "engine/core/file_write.h"
#include "engine/gpu/timer.h"
#include "engine/image_io/compare.h"
#include "engine/image_io/contact_sheet.h"
#include "engine/image_io/image_io.h"
#include "sandbox/lib/bench/accuracy_plot.h"
#include "sandbox/lib/bench/bench_internal.h"
#include "sandbox/lib/bench/bench_methods.h"
#include "sandbox/lib/flavours/lightfield/lightfield_hook.h"
#include "sandbox/lib/render/frame_renderer.h"
#include "sandbox/lib/walk/probe_source.h"

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

namespace fs = std::filesystem;

namespace specula {

std::string skyOnlyPath() {
    return std::string(SPECULA_SOURCE_ROOT) + "/assets/sky_only/sky_only.gltf";
}

std::string truckRoomPath() {
    return std::string(SPECULA_SOURCE_ROOT) + "/assets/truck_room/truck_room.gltf";
}

std::string bowlRoomPath() {
    return std::string(SPECULA_SOURCE_ROOT) + "/assets/bowl_room/bowl_room.gltf";
}

namespace {

std::string machineName() {
    std::ifstream in("/proc/cpuinfo");
    std::string line, model = "unknown CPU";
    while (std::getline(in, line))
        if (line.rfind("model name", 0) == 0) {
            model = line.substr(line.find(':') + 2);
            break;
        }
    return model + ", " + std::to_string(std::thread::hardware_concurrency()) + " hardware threads";
}

double secondsSince(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

std::string num(double v, const char* f = "%.6g") {
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char b[64];
    std::snprintf(b, sizeof b, f, v);
    return b;
}

void writeCsv(const BenchReport& r, const std::vector<MethodErrorBudget>& budgets,
              const std::string& path) {
    std::ostringstream s;
    s << "scene,method,params,ms_median,ratio_to_envmap,frame_ms_median,frame_ratio_to_envmap,"
         "psnr,rmse,psnr_full,rmse_full,"
         "fetches_per_pixel,gpu_bytes,bake_s,frames,width,height,timer"
      << errorBudgetCsvHeader() << "\n";
    for (const BenchRow& b : r.rows) {
        const MethodErrorBudget* budget = nullptr;
        for (const MethodErrorBudget& e : budgets)
            if (e.scene == b.scene && e.method == b.method && e.params == b.params) budget = &e;
        s << b.scene << ',' << b.method << ',' << b.params << ',' << num(b.msMedian) << ','
          << num(b.ratioToEnvmap) << ',' << num(b.frameMsMedian) << ',' << num(b.frameRatioToEnvmap)
          << ',' << formatPsnr(b.psnr, 4) << ',' << num(b.rmse) << ',' << formatPsnr(b.psnrFull, 4)
          << ',' << num(b.rmseFull) << ',' << num(b.fetchesPerPixel) << ',' << b.gpuBytes << ','
          << num(b.bakeSeconds) << ',' << b.frames << ',' << r.width << ',' << r.height << ','
          << (b.method == "groundtruth"     ? "cpu-wall"
              : r.timer == "GL timer query" ? "gl"
                                            : "wall")
          << errorBudgetCsvValues(budget) << '\n';
    }
    writeFileAtomically(path, s.str());
}

void writeMarkdown(const BenchReport& r, const std::vector<std::string>& scenePaths,
                   const std::vector<MethodErrorBudget>& budgets, const std::string& path) {
    std::ostringstream s;
    s << "# Specula bench\n\n"
      << "- machine: " << r.machine << "\n"
      << "- renderer: " << r.renderer << " (OpenGL " << r.glVersion << ")\n"
      << "- frame " << r.width << "x" << r.height << ", distance probe faces " << r.faceRes
      << "^2\n"
      << "- time: " << r.timer << ", median over `frames` frames"
      << (r.timer == "GL timer query"
              ? ""
              : " (this renderer's GL timer queries do not cover its deferred rasterisation)")
      << "; "
         "`x envmap` is that median over the classic environment map's, measured in the same "
         "run. `frame x envmap`: the whole frame (scene, sky and reflectors, wall clock between "
         "glFinish calls) over the envmap row's whole frame. The ground-truth row times the "
         "Embree trace of the frame on the CPU (wall clock). "
         "On a CPU rasteriser (llvmpipe) read the ratios, not the milliseconds.\n"
      << "- error: RGB over the reflector pixels (the ground truth's mirror mask, eroded by one "
         "pixel); `env` against reflections of the environment only (what a probe can hold), "
         "`full` against the multi-bounce ground truth. The ground truth's own `env` PSNR is "
         "inf (identical); its `full` PSNR is the floor any single-bounce probe shares. `none`: "
         "nothing was measured (no reflector pixel, or truth and render both black), never a "
         "perfect score.\n"
      << "- fetches/px: texture fetches per reflector pixel counted by the CPU twin "
         "(CpuDistanceProbe) on the shader's own inputs; the light field's is its fixed 4 "
         "bilinear fetches per ray.\n"
      << "- error budget (distance methods at d_e 0.01): the CPU twin over the truth's "
         "reflector rays, baseline against four experiments that each remove one source of "
         "error: (a) exact search along the stored distances, (b) faces 2x per side, (c) no "
         "radiance filtering across silhouettes, (d) the rays whose truth hit the probe centre "
         "cannot see take the truth. A term is the baseline MSE less the experiment's; "
         "residual: all four at once; interaction: baseline - residual - the terms (0 when "
         "additive); oracle: the lookup handed the truth's hit (the floor of any search); "
         "RGBA16F (e): the baseline's PSNR change with every layer, the composite included, "
         "stored as half floats (against the float32 composite). "
         "bench.csv: the budget_* columns; error_budget.png.\n\n";
    for (const std::string& scene : scenePaths) {
        const std::string name = fs::path(scene).stem().string();
        s << "## " << name << " (`" << fs::path(scene).filename().string() << "`)\n\n"
          << "| method | params | ms median | x envmap | frame x envmap | PSNR env dB | RMSE env | "
             "PSNR full dB | "
             "RMSE full | fetches/px | probe GPU MiB | bake s | frames |\n"
          << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
        for (const BenchRow& b : r.rows) {
            if (b.scene != name) continue;
            s << "| " << b.method << " | " << b.params << " | " << num(b.msMedian, "%.3f") << " | "
              << num(b.ratioToEnvmap, "%.2f")
              << " | "
              // The ground truth has no raster frame: its frame ratio was never measured.
              << (std::isnan(b.frameRatioToEnvmap) ? std::string("n/a")
                                                   : num(b.frameRatioToEnvmap, "%.2f"))
              << " | " << formatPsnr(b.psnr) << " | " << num(b.rmse, "%.4f") << " | "
              << formatPsnr(b.psnrFull) << " | " << num(b.rmseFull, "%.4f") << " | "
              << num(b.fetchesPerPixel, "%.2f") << " | "
              << num(double(b.gpuBytes) / (1024.0 * 1024.0), "%.1f") << " | "
              << num(b.bakeSeconds, "%.2f") << " | " << b.frames << " |\n";
        }
        s << "\n" << errorBudgetMarkdown(budgets, name);
        s << "![strip](strip_" << name << ".png)\n\n";
    }
    s << "![accuracy against time](accuracy_vs_time.png)\n";
    if (!budgets.empty()) s << "\n![error budget](error_budget.png)\n";
    writeFileAtomically(path, s.str());
}

} // namespace

// Texture fetches per reflector pixel, counted by the CPU twin on the shader's own inputs
// (probe-local position and reflected direction read back from the GPU).
double countFetches(FrameRenderer& fr, ReflectionScene& scene, const CameraView& cam,
                    const Image& mask) {
    const Image pos = fr.render(cam, 1);
    const Image dir = fr.render(cam, 2);
    const ecs::Entity probe = scene.probeEntity();
    const DistanceStore* store = fr.probes().store<DistanceStore>();
    const DistanceProbeAsset* asset = store ? store->asset(probe) : nullptr;
    const DistanceLookupConfig* config = store ? store->config(probe) : nullptr;
    if (!asset || !config) return std::numeric_limits<double>::quiet_NaN();
    const CpuDistanceProbe twin(*asset, *config);
    using Sum = std::pair<long long, long long>; // fetches, pixels
    const Sum total = tbb::parallel_reduce(
        tbb::blocked_range2d<int>(0, mask.height, 0, mask.width), Sum{0, 0},
        [&](const tbb::blocked_range2d<int>& r, Sum s) {
            for (int y = r.rows().begin(); y < r.rows().end(); ++y)
                for (int x = r.cols().begin(); x < r.cols().end(); ++x) {
                    if (mask.at(x, y)[0] < 0.5f) continue;
                    int fetches = 0;
                    const glm::vec3 l = glm::vec3(dir.rgba(x, y));
                    if (!(glm::dot(l, l) > 0.5f)) continue;
                    twin.radiance(glm::vec3(pos.rgba(x, y)), glm::normalize(l), fetches);
                    s.first += fetches;
                    ++s.second;
                }
            return s;
        },
        [](Sum a, Sum b) {
            return Sum{a.first + b.first, a.second + b.second};
        });
    return total.second ? double(total.first) / double(total.second) : 0.0;
}

Image measureProbeRow(FrameRenderer& fr, const CameraView& cam, const BenchTruth& truth,
                      BenchFrameBudget budget, BenchRow& row) {
    row.msMedian = timeReflectorPass(fr, cam, budget.minFrames, budget.maxFrames, row.frames,
                                     &row.frameMsMedian);
    Image img = fr.render(cam);
    const ImageStats env = compareImages(img, truth.env.color, &truth.mask);
    const ImageStats full = compareImages(img, truth.full.color, &truth.mask);
    row.psnr = env.psnr, row.rmse = env.rmse;
    row.psnrFull = full.psnr, row.rmseFull = full.rmse;
    row.gpuBytes = fr.stats().probeGpuBytes;
    return img;
}

bool syncBenchProbe(FrameRenderer& fr, ReflectionScene& scene, const BenchRow& row,
                    std::ostream& log) {
    try {
        fr.probes().sync(scene.registry());
        return true;
    } catch (const Error& e) {
        log << "  " << row.scene << " " << row.method << " " << row.params << ": skipped ("
            << e.what() << ")\n";
        return false;
    }
}

void logBenchRow(std::ostream& log, const BenchRow& row) {
    log << "  " << row.scene << " " << row.method << " " << row.params << ": "
        << num(row.msMedian, "%.3f") << " ms (x" << num(row.ratioToEnvmap, "%.2f") << "; frame "
        << num(row.frameMsMedian, "%.3f") << " ms), PSNR " << formatPsnr(row.psnr) << " dB, "
        << num(row.fetchesPerPixel, "%.2f") << " fetches/px\n"
        << std::flush;
}

BenchReport runBench(const BenchOptions& opt, std::ostream& log) {
    const AddedReflectorsScope added(opt.addedReflectors);
    BenchReport report;
    report.width = opt.width ? opt.width : opt.quick ? 160 : 1024;
    report.height = opt.height ? opt.height : opt.quick ? 120 : 768;
    report.faceRes = opt.faceRes ? opt.faceRes : opt.quick ? 64 : 256;
    const int maxFrames = opt.maxFrames ? opt.maxFrames : opt.quick ? 12 : 64;
    const int minFrames = std::min(maxFrames, opt.quick ? 6 : 16);
    const int gtRuns = opt.quick ? 1 : 3;
    std::vector<std::string> scenes = opt.scenes;
    if (scenes.empty())
        scenes = {defaultScenePath(), truckRoomPath(), bowlRoomPath(), skyOnlyPath()};
    const std::string sky = opt.sky.empty() ? defaultSkyPath() : opt.sky;
    for (const std::string& s : scenes)
        if (!fs::exists(s)) throw Error(s, "", "no such scene");
    fs::create_directories(opt.outDir);

    auto context = gpu::GlContext::createHeadless();
    report.machine = machineName();
    report.renderer = context->renderer();
    report.glVersion = context->version();
    std::vector<PlotPanel> panels;
    std::vector<MethodErrorBudget> budgets;
    std::vector<std::string> sceneNames;

    for (const std::string& scenePath : scenes) {
        const std::string name = fs::path(scenePath).stem().string();
        ReflectionScene scene(scenePath, sky);
        if (scene.markup().reflectors.empty())
            throw Error(scenePath, "specula_reflector",
                        "the scene has no reflector node (mark one with specula_reflector, or "
                        "add one with --add-reflector sphere:x,y,z,r)");
        if (!opt.addedReflectors.empty())
            log << name << ": " << opt.addedReflectors.size()
                << " reflector(s) added (--add-reflector)\n";
        const std::string probeDir = (fs::path(opt.outDir) / "probes" / name).string();
        log << name << ": baking the distance probe (" << report.faceRes << "^2 faces)\n"
            << std::flush;
        const double bakeSeconds =
            bakeDistanceProbeInto(scene, probeDir, report.faceRes, opt.progress, false, &log);
        const std::string planDir = probeDir + "_plan";
        const double planBakeSeconds =
            bakeDistanceProbeInto(scene, planDir, report.faceRes, opt.progress, true, &log);
        log << name << ": baking the light fields\n" << std::flush;
        std::vector<LightFieldBake> lfs;
        try {
            lfs = bakeLightFieldsForBench(
                scene, (fs::path(opt.outDir) / "probes" / (name + "_lightfield")).string(),
                opt.quick, &log);
        } catch (const Error& e) {
            log << name << ": no light-field rows (" << e.what() << ")\n";
        }
        BenchSweep sweep;
        if (opt.quick) sweep.tolerances = {0.1f, 0.01f};
        for (const LightFieldBake& b : lfs)
            sweep.lightFields.push_back(b.params);
        const std::vector<MethodVariant> variants = benchVariants(sweep);

        const CameraView cam = scene.camera(report.width, report.height);
        log << name << ": tracing the ground truth\n" << std::flush;
        std::vector<double> gtMs;
        GroundTruthImage envTruth;
        for (int i = 0; i < gtRuns; ++i) {
            const auto t0 = std::chrono::steady_clock::now();
            envTruth = scene.groundTruth(cam, true);
            gtMs.push_back(1000.0 * secondsSince(t0));
        }
        const GroundTruthImage fullTruth = scene.groundTruth(cam, false);
        const Image mask = erodedMask(envTruth.mirrorMask);
        const ImageStats maskCheck = compareImages(envTruth.color, envTruth.color, &mask);
        if (maskCheck.pixels == 0)
            throw Error(scenePath, "camera", "the camera sees no reflector pixel");

        const BenchTruth truth{envTruth, fullTruth, mask};
        const BenchFrameBudget budget{minFrames, maxFrames};
        FrameRenderer fr(scene, report.width, report.height);
        report.timer = fr.timerSource();
        double envmapMs = std::numeric_limits<double>::quiet_NaN();
        std::map<std::string, Image> shots; // for the strip
        PlotPanel panel;
        panel.title = name + "  (" + std::to_string(report.width) + "x" +
                      std::to_string(report.height) + ", " + report.renderer.substr(0, 40) + ")";
        for (const MethodVariant& v : variants) {
            BenchRow row;
            row.scene = name;
            row.method = v.method;
            row.params = v.params;
            if (v.kind == VariantKind::GroundTruth) {
                row.msMedian = gpu::medianMs(gtMs);
                row.frames = int(gtMs.size());
                const ImageStats self = compareImages(envTruth.color, envTruth.color, &mask);
                const ImageStats full = compareImages(envTruth.color, fullTruth.color, &mask);
                row.psnr = self.psnr, row.rmse = self.rmse;
                row.psnrFull = full.psnr, row.rmseFull = full.rmse;
                row.fetchesPerPixel = 0;
                shots["groundtruth"] = envTruth.color;
            } else {
                const LightFieldBake* lf =
                    v.lightField >= 0 ? &lfs[std::size_t(v.lightField)] : nullptr;
                const std::string asset = lf          ? lf->manifest
                                          : v.planned ? planDir + "/manifest.json"
                                                      : probeDir + "/manifest.json";
                if (lf)
                    scene.setProbe(asset, LightFieldProbe{});
                else
                    scene.setProbe(asset, v.distance);
                if (!syncBenchProbe(fr, scene, row, log)) continue;
                const Image img = measureProbeRow(fr, cam, truth, budget, row);
                row.bakeSeconds = lf ? lf->seconds : v.planned ? planBakeSeconds : bakeSeconds;
                row.fetchesPerPixel = lf ? lf->fetchesPerPixel : countFetches(fr, scene, cam, mask);
                const std::string key = v.method + " " + v.params;
                shots[key] = img;
                if (v.method == "envmap") envmapMs = row.msMedian;
            }
            row.ratioToEnvmap = row.msMedian / envmapMs;
            logBenchRow(log, row);
            if (v.kind != VariantKind::GroundTruth)
                panel.points.push_back({row.method, row.params, row.ratioToEnvmap, row.psnr});
            report.rows.push_back(row);
        }
        appendFormatRows(scene, fr, cam, truth, budget, name, probeDir, variants, envmapMs, report,
                         log);
        // The PEM sweep N in {4, 8, 16, 32} on the room and the concave bowl (self- and
        // inter-reflection), N = 8 elsewhere and in quick runs, or the --pem-samples given;
        // faces as the distance probes' but at most 256 (the inference goal is stated at 256^2).
        const bool sampleSweep =
            !opt.quick && (scenePath == defaultScenePath() || scenePath == bowlRoomPath());
        PemBenchSweep pemSweep;
        pemSweep.samples = !opt.pemSamples.empty() ? opt.pemSamples
                           : sampleSweep           ? std::vector<int>{4, 8, 16, 32}
                                                   : std::vector<int>{8};
        pemSweep.faceRes = std::min(report.faceRes, 256);
        pemSweep.width = report.width;
        pemSweep.height = report.height;
        pemSweep.supersample = opt.pemSupersample;
        pemSweep.rows = opt.pemRows;
        pemSweep.nonNegative = opt.pemNonNegative;
        pemSweep.roundingReach = opt.pemRoundingReach;
        pemSweep.cameraPath = opt.pemPath == kCameraPathName ||
                              (opt.pemPath == "auto" && sceneCameraMoves(scene.probeScene()));
        // The best single-bounce method of the sweep (layered, else bisection, d_e 0.01) drawn
        // from the PEM's cameras too.
        for (const char* method : {"bisection", "layered"})
            for (const MethodVariant& v : variants)
                if (v.method == method && v.params == formatTolerance(0.01f) && !v.planned &&
                    std::any_of(report.rows.begin(), report.rows.end(), [&](const BenchRow& r) {
                        return r.scene == name && r.method == v.method && r.params == v.params;
                    })) {
                    pemSweep.reference = v;
                    pemSweep.referenceAsset = probeDir + "/manifest.json";
                    pemSweep.referenceBakeSeconds = bakeSeconds;
                }
        appendErrorBudgets(scene, cam, truth, name, probeDir, report.faceRes, opt.progress,
                           variants, report.rows, budgets, log);
        sceneNames.push_back(name);
        appendPemRows(scene, fr, name, opt.outDir, pemSweep, budget, envmapMs, report, panel, log);
        panels.push_back(panel);

        // Strip: ground truth | envmap | boxproj | distance cubemap (layered, d_e 0.01) | light
        // field
        // (largest cooked), heat maps below.
        const std::string distanceKey = "layered " + formatTolerance(0.01f);
        std::vector<std::pair<std::string, std::string>> columns = {
            {"groundtruth", "ground truth (Embree)"},
            {"envmap -", "envmap"},
            {"boxproj -", "boxproj"},
            {shots.count(distanceKey) ? distanceKey
                                      : std::string("bisection ") + formatTolerance(0.01f),
             std::string(shots.count(distanceKey) ? "layered" : "bisection") + " 0.01"},
        };
        if (!lfs.empty() && shots.count("lightfield " + lfs.back().params))
            columns.push_back({"lightfield " + lfs.back().params, "light field"});
        std::vector<Image> tiles, heat;
        std::vector<std::string> labels, heatLabels;
        for (const auto& [key, label] : columns) {
            if (!shots.count(key)) continue;
            const Image& img = shots[key];
            const ImageStats st = compareImages(img, envTruth.color, &mask);
            tiles.push_back(img);
            labels.push_back(label +
                             (st.hasPsnr ? " " + formatPsnr(st.psnr, 1) + " dB" : " (no PSNR)"));
            heat.push_back(errorHeatmap(img, envTruth.color, &mask, 0.25f));
            heatLabels.push_back("error (red >= 0.25)");
        }
        const int n = int(tiles.size());
        tiles.insert(tiles.end(), heat.begin(), heat.end());
        labels.insert(labels.end(), heatLabels.begin(), heatLabels.end());
        writeImage((fs::path(opt.outDir) / ("strip_" + name + ".png")).string(),
                   contactSheet(tiles, labels, n, std::min(report.width, 400)));
    }

    // Frame ratios: each row's whole frame over its scene's envmap frame (the envmap row's
    // frame is only known once measured, and the PEM rows are appended elsewhere).
    for (BenchRow& row : report.rows)
        for (const BenchRow& e : report.rows)
            if (e.scene == row.scene && e.method == "envmap" && e.params == "-" &&
                e.frameMsMedian > 0)
                row.frameRatioToEnvmap = row.frameMsMedian / e.frameMsMedian;
    writeCsv(report, budgets, (fs::path(opt.outDir) / "bench.csv").string());
    writeMarkdown(report, scenes, budgets, (fs::path(opt.outDir) / "bench.md").string());
    if (!budgets.empty())
        writeImage((fs::path(opt.outDir) / "error_budget.png").string(),
                   errorBudgetPlot(budgets, sceneNames));
    writeImage((fs::path(opt.outDir) / "accuracy_vs_time.png").string(), accuracyPlot(panels));
    return report;
}

} // namespace specula
