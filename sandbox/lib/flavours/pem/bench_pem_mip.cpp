#include "components/reflection_probe/pem/pem_map_levels.h"
#include "components/reflection_probe/pem/pem_probe.h"
#include "components/reflection_probe/pem/writer/pem_probe_writer.h"
#include "engine/core/error.h"
#include "sandbox/lib/bench/bench_internal.h"
#include "sandbox/lib/walk/probe_source.h"

#include <cstdio>
#include <filesystem>

namespace fs = std::filesystem;

namespace specula {

namespace {

// The level-0 bake's maps with their box-filtered chain of `levels` (what a renderer makes on
// the fly from level 0: the paper's reference), local layers as baked.
PemAsset filteredMipAsset(const PemAsset& level0, int levels) {
    PemAsset a = level0;
    a.mipLevels = levels;
    for (PemSampleMap& s : a.samples)
        s.map = pemFilteredMips(s.map, levels);
    return a;
}

// One row of `manifest` at parameter t, as appendPemRows measures its rows.
BenchRow measurePemRow(ReflectionScene& scene, FrameRenderer& fr, const std::string& sceneName,
                       const PemBenchSweep& sweep, const std::string& manifest,
                       const PemAsset& asset, float t, const std::string& params,
                       BenchFrameBudget budget, double envmapMs) {
    const CameraView cam = pemBenchCamera(scene, sweep, t);
    BenchTruth truth{scene.groundTruth(cam, true), scene.groundTruth(cam, false), Image{}};
    truth.mask = erodedMask(truth.env.mirrorMask);
    PemProbe probe;
    probe.parameter = t;
    scene.setProbe(manifest, probe);
    fr.probes().sync(scene.registry());
    BenchRow row;
    row.scene = sceneName;
    row.method = kPemMethods[0].label.name;
    row.params = params;
    measureProbeRow(fr, cam, truth, budget, row);
    row.fetchesPerPixel = pemFetchesPerPixel(scene.probeScene(), cam, asset, probe);
    row.ratioToEnvmap = row.msMedian / envmapMs;
    return row;
}

} // namespace

void appendPemMipRows(ReflectionScene& scene, FrameRenderer& fr, const std::string& sceneName,
                      const std::string& outDir, const PemBenchSweep& sweep, int samples,
                      const CookResult& level0, BenchFrameBudget budget, double envmapMs,
                      BenchReport& report, PlotPanel& panel, std::ostream& log) {
    const PemAsset& baked = std::get<PemAsset>(level0.asset);
    const int levels = PemMap::maxLevels(baked.faceRes);
    const std::string base =
        (fs::path(outDir) / "probes" / (sceneName + "_pem" + std::to_string(samples))).string();
    PemCookSettings settings = pemBenchSettings(sweep, samples);
    settings.localLayer = baked.localLayer ? "on" : "off"; // as the level-0 bake decided
    settings.mipLevels = levels;
    const PemAsset filtered = filteredMipAsset(baked, levels);
    CookResult mip;
    try {
        mip = cookSceneInto(scene, base + "_mip", settings, false, &log);
        writePemProbe(filtered, base + "_filtered", scene.probeScene().path);
    } catch (const Error& e) {
        log << sceneName << ": no PEM MIP rows (" << e.what() << ")\n";
        return;
    }
    const std::string filteredManifest = base + "_filtered/manifest.json";
    double infer0 = 0, inferMip = 0;
    for (const PemSampleFit& f : level0.pemFits)
        infer0 += f.inferSeconds;
    for (const PemSampleFit& f : mip.pemFits)
        inferMip += f.inferSeconds;
    const double n = double(std::max<std::size_t>(mip.pemFits.size(), 1));
    // Full-truth and environment-only dB, on the manifold and half-way: level 0 alone (the
    // appendPemRows rows of this bake), the filtered chain, the inferred levels.
    double full[3][2] = {}, env[3][2] = {};
    const std::string manifests[3] = {level0.manifest, filteredManifest, mip.manifest};
    const PemAsset* assets[3] = {&baked, &filtered, &std::get<PemAsset>(mip.asset)};
    const char* labels[3] = {"", " filtered-mip", " mip"};
    const float half = pemBenchHalfWay(sweep, samples);
    for (int v = 0; v < 3; ++v)
        for (int w = 0; w < 2; ++w) {
            const float t = w == 0 ? 0.f : half;
            BenchRow row = measurePemRow(scene, fr, sceneName, sweep, manifests[v], *assets[v], t,
                                         "N=" + std::to_string(samples) +
                                             " t=" + (w == 0 ? "on" : "off") + labels[v],
                                         budget, envmapMs);
            full[v][w] = row.psnrFull;
            env[v][w] = row.psnr;
            if (v == 0) continue; // appendPemRows reported the level-0 rows already
            row.bakeSeconds = v == 2 ? mip.bakeSeconds : level0.bakeSeconds;
            logBenchRow(log, row);
            panel.points.push_back({row.method, row.params, row.ratioToEnvmap, row.psnr});
            report.rows.push_back(row);
        }
    const double kib0 = double(PemMap::texelCount(baked.faceRes)) * 12.0 / 1024.0;
    const double kibMip = double(PemMap::texelCount(baked.faceRes, levels)) * 12.0 / 1024.0;
    char line[640];
    std::snprintf(line, sizeof line,
                  "%s: PEM N=%d MIP levels (%d, %d^2 faces down): dB full on/off | env on/off: "
                  "level 0 alone %.2f/%.2f | %.2f/%.2f; filtered MIPs %.2f/%.2f | %.2f/%.2f; "
                  "inferred MIPs %.2f/%.2f | %.2f/%.2f (%+.2f/%+.2f dB full over filtered); "
                  "inference %.2f s a sample with MIPs, %.2f s level 0 alone; %.0f KiB a "
                  "distant map with MIPs, %.0f KiB level 0 (float texels)\n",
                  sceneName.c_str(), samples, levels, baked.faceRes, full[0][0], full[0][1],
                  env[0][0], env[0][1], full[1][0], full[1][1], env[1][0], env[1][1], full[2][0],
                  full[2][1], env[2][0], env[2][1], full[2][0] - full[1][0],
                  full[2][1] - full[1][1], inferMip / n,
                  infer0 / double(std::max<std::size_t>(level0.pemFits.size(), 1)), kibMip, kib0);
    log << line << std::flush;
}

} // namespace specula
