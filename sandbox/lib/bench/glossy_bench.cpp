#include "sandbox/lib/bench/glossy_bench.h"
#include "assetcooker/lib/scene/reflector_roughness_maps.h"

#include "assetcooker/lib/bake/cook.h"
#include "assetcooker/lib/scene/reflector_pixels.h"
#include "components/reflection_probe/distance/distance_glossy_cpu.h"
#include "components/reflection_probe/distance/system/distance_store.h"
#include "components/reflection_probe/lightfield/lightfield_probe_cpu.h"
#include "components/reflection_probe/system/reflector_roughness.h"
#include "engine/context/context.h"
#include "engine/core/error.h"
#include "engine/core/file_write.h"
#include "engine/image/ggx_albedo.h"
#include "engine/image_io/compare.h"
#include "engine/raytrace/ground_truth.h"
#include "sandbox/lib/bench/glossy_timing.h"
#include "sandbox/lib/render/reflection_scene.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <sstream>

namespace specula {
namespace sandbox {

namespace fs = std::filesystem;

namespace {

// NaN (printed "none") when nothing was measured: no reflector pixel in view, or black
// against black (ImageStats); never 0 dB, which would read as a dreadful score.
double clampedPsnr(const ImageStats& s) {
    return s.hasPsnr ? std::min(s.psnr, 99.0) : std::numeric_limits<double>::quiet_NaN();
}

// A line a roughness (the rows hold one per method, in `methods` order), a column a method.
template <class Cell>
void printByRoughness(std::ostream& log, const std::vector<std::string>& methods,
                      const std::vector<GlossyBenchRow>& rows, bool noiseColumn, Cell cell) {
    log << std::left << std::setw(6) << "r";
    if (noiseColumn) log << std::setw(8) << "noise";
    for (const std::string& m : methods)
        log << " | " << std::setw(27) << m;
    log << '\n';
    for (std::size_t i = 0; i + methods.size() <= rows.size(); i += methods.size()) {
        std::ostringstream r;
        r << rows[i].roughness;
        log << std::setw(6) << r.str();
        if (noiseColumn) log << std::setw(8) << formatPsnr(rows[i].noiseFloorPsnr);
        for (std::size_t m = 0; m < methods.size(); ++m)
            log << " | " << std::setw(27) << cell(rows[i + m]);
        log << '\n';
    }
    log << std::right;
}

} // namespace

const std::vector<std::string>& glossyBenchMethods() {
    static const std::vector<std::string> methods{"envmap+chain",
                                                  "boxproj+chain",
                                                  "rectified (roughness level)",
                                                  "rectified (footprint level)",
                                                  "layered (footprint level)",
                                                  "light field glossy"};
    return methods;
}

std::vector<float> parseRoughnessList(const std::string& text) {
    std::vector<float> out;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');) {
        item.erase(0, item.find_first_not_of(" \t"));
        item.erase(item.find_last_not_of(" \t") + 1);
        std::size_t used = 0;
        float r = std::numeric_limits<float>::quiet_NaN();
        try {
            r = std::stof(item, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (item.empty() || used != item.size() || !std::isfinite(r) || r < 0.f || r > 1.f)
            throw UsageError("--roughness", "expected perceptual roughness values in [0, 1] "
                                            "separated by commas, got '" +
                                                item + "'");
        out.push_back(r);
    }
    if (out.empty())
        throw UsageError("--roughness",
                         "expected one roughness value at least, got '" + text + "'");
    return out;
}

GlossyBenchResult runGlossyBench(const GlossyBenchOptions& o, std::ostream& log) {
    using Clock = std::chrono::steady_clock;
    ReflectionScene reflectionScene(o.scene, o.sky, o.addedReflectors);
    ProbeScene& scene = reflectionScene.probeScene();
    for (const AddedReflector& r : o.addedReflectors)
        log << "added " << describeAddedReflector(r) << '\n';
    if (scene.markup.mirrorEntities.empty())
        throw Error(scene.path, "specula_reflector", "the scene has no reflector to look up");
    fs::create_directories(o.out);
    GlossyBenchResult result;

    // The two probes, baked once through the cooking API into DIR/probes.
    const auto bakeStart = Clock::now();
    CookOptions cook;
    cook.progress = o.progress;
    DistanceCookSettings d;
    d.faceRes = o.faceRes;
    d.planned = d.recordPlan = false;
    d.glossy = GlossyBake::On;
    cook.flavour = d;
    cook.out = (fs::path(o.out) / "probes" / "distance").string();
    const CookResult distanceCook = cookProbe(scene, cook, &log);
    const DistanceProbeAsset& distanceAsset = std::get<DistanceProbeAsset>(distanceCook.asset);
    LightFieldCookSettings lfSettings;
    lfSettings.cameras = 8;
    lfSettings.imageRes = 64;
    cook.flavour = lfSettings;
    cook.out = (fs::path(o.out) / "probes" / "lightfield").string();
    const CookResult lightFieldCook = cookProbe(scene, cook, &log);
    const LightFieldAsset& lightFieldAsset = std::get<LightFieldAsset>(lightFieldCook.asset);
    result.bakeSeconds = std::chrono::duration<double>(Clock::now() - bakeStart).count();
    const glm::vec3 cell = lightFieldCook.cellCentre;
    log << "light-field cell: " << lightFieldCook.cellSize << " m around (" << cell.x << ", "
        << cell.y << ", " << cell.z << ")\n";
    for (const LightFieldIntrusion& i : lightFieldAsset.intrusions)
        if (i.region == "cell")
            log << "warning: " << i.object << " lies in the light-field cell (reaches "
                << std::abs(i.depth) << " m): reflectors there see it wrongly\n";
    for (const ReflectorOverhang& h : lightFieldCook.overhangs)
        log << "warning: reflector '" << h.node << "' reaches " << h.metres
            << " m outside the light-field cell (the light field is exact only inside)\n";
    log << "baked the distance probe (" << o.faceRes << "^2 faces) and the light field (8 x 8 "
        << "cameras of 64^2) in " << std::fixed << std::setprecision(1) << result.bakeSeconds
        << " s" << std::defaultfloat << std::setprecision(6) << '\n';

    DistanceProbe search;
    search.method = DistanceMethod::Secant;
    search.errorTolerance = 0.01f;
    const CpuGlossyDistanceProbe distance(distanceAsset, search);
    // Layered: the object layers as the store holds them (half floats), the same chain.
    const DistanceProbeAsset storedAsset = storedDistanceAsset(distanceAsset);
    const CpuDistanceProbe layered(storedAsset,
                                   makeLookupConfig(layeredSearch(search), storedAsset),
                                   std::make_shared<const CubeChain>(distance.chain()));
    const CpuLightFieldProbe lightField(lightFieldAsset);

    const CameraView camera = reflectionScene.camera(o.width, o.height);
    const std::vector<std::string>& methods = glossyBenchMethods();
    const GlossyTextures textures =
        glossyTextures(distanceAsset, distance.chain(), lightFieldAsset, scene.markup);
    const ReflectorRoughnessMaps maps(scene.markup);
    for (const float r : o.roughness) {
        TraceOptions t = groundTruthOptions(scene, true);
        t.mirrorRoughness = [r, &maps](ecs::Entity e, glm::vec2 uv) { return maps.at(r, e, uv); };
        t.glossySamples = o.samples;
        t.seed = 1;
        const GroundTruthTracer tracer(scene.registry, t);
        const GroundTruthImage truth = tracer.render(camera, 1);
        const Image mask = erodedMask(truth.mirrorMask);
        // The truth against itself with another seed; exact at roughness 0.
        const double noise =
            r > 0.f ? clampedPsnr(compareImages(tracer.render(camera, 2).color, truth.color, &mask))
                    : std::numeric_limits<double>::infinity();
        const std::vector<ReflectorPixel> pixels =
            reflectorPixels(tracer, camera, truth.mirrorMask);
        result.mirrorPixels = long(pixels.size());
        // The distance methods: the normalised prefiltered lighting times the directional
        // albedo, as the shaders do (E = 1 for a mirror), at the pixel's own roughness.
        const auto footprint = [&](const ReflectorPixel& p, float rp) {
            const float e = rp > 0.f ? ggxAlbedo(std::min(p.cosView(), 1.f), rp) : 1.f;
            return e * distance.radiance(p.position - distanceAsset.centre, p.lhat, rp,
                                         GlossyMode::RectifiedFootprint);
        };
        for (std::size_t m = 0; m < methods.size(); ++m) {
            Image img = truth.color;
            const GlossyBenchMethod method = GlossyBenchMethod(m);
            for (const ReflectorPixel& p : pixels) {
                glm::vec3 c;
                const float rp = maps.at(r, p.entity, p.uv);
                const float e = rp > 0.f ? ggxAlbedo(std::min(p.cosView(), 1.f), rp) : 1.f;
                const glm::vec3 x = p.position - distanceAsset.centre;
                if (method == GlossyBenchMethod::RectifiedFootprint) {
                    c = footprint(p, rp);
                } else if (m < kGlossyModes.size()) {
                    c = e * distance.radiance(x, p.lhat, rp, kGlossyModes[m]);
                } else if (method == GlossyBenchMethod::LayeredFootprint) {
                    c = e * layered.glossySample(x, p.lhat, rp).radiance;
                } else {
                    c = lightField.reflectedRadiance(p.position - lightFieldAsset.cellCentre,
                                                     p.lhat, p.normal, rp);
                }
                std::copy(&c[0], &c[0] + 3, img.at(p.x, p.y));
            }
            GlossyBenchRow row;
            row.roughness = r;
            row.method = methods[m];
            row.psnr = clampedPsnr(compareImages(img, truth.color, &mask));
            row.noiseFloorPsnr = noise;
            row.memoryMiB = double(textures.bytes(method, r)) / (1024.0 * 1024.0);
            result.rows.push_back(row);
        }
        log << "roughness " << r << ": " << pixels.size() << " reflector pixels, truth noise floor "
            << formatPsnr(noise) << " dB\n";
        if (!maps.empty()) {
            // The footprint row again, each mapped reflector at factor x its map's mean.
            Image img = truth.color;
            for (const ReflectorPixel& p : pixels) {
                const glm::vec3 c = footprint(p, maps.mean(r, p.entity));
                std::copy(&c[0], &c[0] + 3, img.at(p.x, p.y));
            }
            GlossyMapVsMean v;
            v.roughness = r;
            v.mapPsnr = result
                            .rows[result.rows.size() - methods.size() +
                                  std::size_t(GlossyBenchMethod::RectifiedFootprint)]
                            .psnr;
            v.meanPsnr = clampedPsnr(compareImages(img, truth.color, &mask));
            result.mapVsMean.push_back(v);
            log << "roughness " << r << ": rectified (footprint level) " << formatPsnr(v.mapPsnr)
                << " dB with the roughness maps, " << formatPsnr(v.meanPsnr)
                << " dB with each map's mean roughness (uniform)\n";
        }
    }

    if (o.timing) {
        const auto context = gpu::GlContext::createHeadless();
        const GlossyTiming timing =
            timeGlossyPasses(reflectionScene, distanceCook.manifest, lightFieldCook.manifest,
                             search, camera, o.roughness, textures, o.timingRounds);
        for (const GlossyPassTime& t : timing.passes)
            for (GlossyBenchRow& row : result.rows)
                if (row.roughness == t.roughness && row.method == methods[std::size_t(t.method)])
                    row.ratioToEnvmap = t.ratioToEnvmap;
        result.envmapMs = timing.envmapMs;
        result.timer = timing.timer;
        result.storeBytes = timing.storeBytes;
        result.expectedStoreBytes = timing.expectedStoreBytes;
        if (timing.storeBytes != timing.expectedStoreBytes)
            log << "warning: the probe stores hold " << timing.storeBytes
                << " bytes of textures, the memory column counts " << timing.expectedStoreBytes
                << '\n';
    }
    std::ostringstream csv;
    csv << "roughness,method,psnr,noise_floor_psnr,ratio_to_envmap,memory_mib\n";
    for (const GlossyBenchRow& row : result.rows) {
        csv << row.roughness << ",\"" << row.method << "\"," << formatPsnr(row.psnr) << ','
            << formatPsnr(row.noiseFloorPsnr) << ',';
        if (row.ratioToEnvmap >= 0.0)
            csv << row.ratioToEnvmap;
        else
            csv << "none";
        csv << ',' << row.memoryMiB << '\n';
    }

    // The table: a row per roughness, a column per method.
    log << "\nPSNR (dB) against the GGX truth (environment only, " << o.samples
        << " samples) on the reflector pixels\n";
    printByRoughness(log, methods, result.rows, true,
                     [](const GlossyBenchRow& row) { return formatPsnr(row.psnr); });
    log << "\nreflector pass / mirror envmap pass"
        << (result.timer.empty() ? std::string(" (not timed)")
                                 : " (" + result.timer + "; the mirror envmap pass " +
                                       std::to_string(result.envmapMs) + " ms)")
        << "; texture MiB\n";
    printByRoughness(log, methods, result.rows, false, [](const GlossyBenchRow& row) {
        std::ostringstream cell;
        cell << std::fixed << std::setprecision(2);
        if (row.ratioToEnvmap >= 0.0)
            cell << row.ratioToEnvmap << "x";
        else
            cell << "-";
        cell << ", " << row.memoryMiB << " MiB";
        return cell.str();
    });
    writeFileAtomically((fs::path(o.out) / "glossy.csv").string(), csv.str());
    log << "-> " << o.out << "/glossy.csv\n";
    return result;
}

} // namespace sandbox
} // namespace specula
