#include "sandbox/lib/flavours/distance/level_walk.h"
#include "assetcooker/lib/scene/reflector_roughness_maps.h"

#include "assetcooker/lib/level/level_bake.h"
#include "assetcooker/lib/scene/probe_setup.h"
#include "assetcooker/lib/scene/reflector_pixels.h"
#include "components/reflection_probe/distance/distance_level.h"
#include "components/reflection_probe/distance/distance_level_cpu.h"
#include "components/reflection_probe/distance/distance_textures.h"
#include "components/reflection_probe/system/reflector_roughness.h"
#include "engine/context/context.h"
#include "engine/core/error.h"
#include "engine/core/file_write.h"
#include "engine/core/progress.h"
#include "engine/image/ggx_albedo.h"
#include "engine/image_io/compare.h"
#include "engine/image_io/contact_sheet.h"
#include "engine/image_io/image_io.h"
#include "sandbox/lib/flavours/distance/level_timing.h"
#include "sandbox/lib/render/reflection_scene.h"
#include "sandbox/lib/walk/chase_path.h"

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

constexpr std::array<LevelBlend, 3> kBlends{LevelBlend::Nearest, LevelBlend::Engine,
                                            LevelBlend::Visibility};

double rmsChange(const Image& a, const Image& b, const Image& maskA, const Image& maskB) {
    double sum = 0;
    std::size_t n = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            if (maskA.at(x, y)[0] < 0.5f || maskB.at(x, y)[0] < 0.5f) continue;
            for (int c = 0; c < 3; ++c) {
                const double d = double(a.at(x, y)[c]) - double(b.at(x, y)[c]);
                sum += d * d;
            }
            n += 3;
        }
    return n ? std::sqrt(sum / double(n)) : 0.0;
}

std::string weightsText(const CpuDistanceLevel& level, const LevelSample& s) {
    std::ostringstream t;
    t << std::fixed << std::setprecision(3);
    for (const auto& [i, w] : s.weights)
        t << (t.tellp() > 0 ? " " : "") << level.volumes()[std::size_t(i)].name << ':' << w;
    if (s.sky > 0.f) t << (t.tellp() > 0 ? " " : "") << "sky:" << s.sky;
    return t.str();
}

// A frame's PSNR on the reflector pixels: NaN ("none") when there is none (no reflector
// pixel in view, or black against black), never a number that reads as a score.
double framePsnr(const ImageStats& st) {
    return st.hasPsnr ? std::min(st.psnr, 99.0) : std::numeric_limits<double>::quiet_NaN();
}

struct FrameImages {
    Image truth, mask;
    std::array<Image, 3> blends;
};

// The sky a baked level's first probe holds (every probe of a level is baked under one):
// its file in the probe's folder, "" (black) when it holds none.
std::string levelSkyPath(const std::string& levelDir) {
    const fs::path index = fs::path(levelDir) / "level.json";
    const LevelIndex level = readLevelIndex(index.string());
    if (level.probes.empty()) throw Error(index.string(), "probes", "the level has no probe");
    const fs::path folder = fs::path(levelDir) / level.probes.front().folder;
    const DistanceProbeAsset first = readDistanceProbe((folder / "manifest.json").string());
    return first.skyFile.empty() ? "" : (folder / first.skyFile).string();
}

} // namespace

LevelWalkResult runLevelWalk(const LevelWalkOptions& o, std::ostream& log) {
    ReflectionScene reflectionScene(o.scene, o.skyFromLevel ? levelSkyPath(o.level) : o.sky,
                                    o.addedReflectors);
    ProbeScene& scene = reflectionScene.probeScene();
    for (const AddedReflector& r : o.addedReflectors)
        log << "added " << describeAddedReflector(r) << '\n';
    fs::create_directories(o.out);
    LevelWalkResult result;
    std::string levelDir = o.level;
    if (levelDir.empty()) {
        levelDir = (fs::path(o.out) / "level").string();
        LevelCookOptions lc;
        lc.cook.scene = scene.path;
        lc.cook.sky = scene.skyPath;
        lc.cook.out = levelDir;
        DistanceCookSettings d;
        d.faceRes = o.faceRes;
        d.planned = false;
        lc.cook.flavour = d;
        lc.cook.progress = o.progress;
        lc.sources.positions = o.probes;
        lc.sources.file = o.probeList;
        const LevelCookResult r = cookLevel(scene, lc, &log);
        for (const LevelProbeOutcome& p : r.probes)
            result.bakeSeconds += p.seconds;
    }
    const DistanceMethodInfo* method = findDistanceMethod(o.method);
    if (!method) throw UsageError("--method", "unknown method '" + o.method + "'");
    DistanceProbe settings;
    settings.method = method->method;
    settings.errorTolerance = o.tolerance;
    // A rough reflector reads every probe's chain (made here as the store makes it).
    const bool rough = o.roughness > 0.f;
    const std::string indexPath = (fs::path(levelDir) / "level.json").string();
    const LevelIndex index = readLevelIndex(indexPath);
    if (index.probes.empty()) throw Error(indexPath, "probes", "the level has no probe to walk");
    if (!o.level.empty()) {
        // A level walked against another scene than it was baked from measures nothing true.
        const std::vector<std::string> stale =
            levelStaleness(scene, index, indexPath, !o.skyFromLevel);
        for (const std::string& line : stale)
            log << (o.allowStale ? "warning: " : "error: ") << line << '\n';
        if (!stale.empty() && !o.allowStale)
            throw Error(indexPath, "probes",
                        std::to_string(stale.size()) +
                            " input(s) differ from the scene walked (listed "
                            "above): re-bake the level with specula-cook "
                            "bake, or pass --allow-stale");
    }
    const CpuDistanceLevel level(indexPath, settings, rough);
    {
        // What the level store holds on the GPU: the composites and the sky, plus a rough
        // reflector's chains (DistanceLevelStore::gpuBytesOf).
        const DistanceProbeAsset first = readDistanceProbe(
            (fs::path(levelDir) / index.probes.front().folder / "manifest.json").string());
        const int n = int(level.volumes().size());
        result.mirrorBytes =
            cubeArrayBytes(first.faceRes, n) + (first.sky.empty() ? 0 : skyTextureBytes(first.sky));
        result.chainBytes = rough ? std::size_t(n) * chainArrayBytes(*level.glossyChain(0)) : 0;
        log << "level textures: " << double(result.mirrorBytes) / (1024.0 * 1024.0)
            << " MiB (composites and sky)";
        if (rough)
            log << " + " << double(result.chainBytes) / (1024.0 * 1024.0) << " MiB of chains (" << n
                << " probes) at roughness " << o.roughness;
        log << '\n';
    }

    std::vector<glm::vec3> points = o.path;
    if (points.empty())
        for (const ProbeVolume& v : level.volumes())
            points.push_back(v.position);
    if (points.size() < 2)
        throw UsageError("--path", "a walk needs two points at least: the level has " +
                                       std::to_string(level.volumes().size()) +
                                       " probe(s); give --path x,y,z;x,y,z;...");
    const Polyline path(points);
    ReflectorRoots roots(scene);
    if (roots.roots().empty())
        throw Error(scene.path, "specula_reflector", "the scene has no reflector node to walk");
    const glm::vec3 anchor = roots.roots().front().second;

    // --roughness is each reflector's factor; a roughness map multiplies it per pixel.
    const ReflectorRoughnessMaps maps(scene.markup);
    const int frames = std::max(2, o.frames);
    float side = 1.f;
    {
        const EmbreeScene env(scene.registry, [&](ecs::Entity e) {
            return scene.markup.mirrorEntities.count(e) == 0;
        });
        if (unblockedFrames(env, path, -1.f, frames) > unblockedFrames(env, path, 1.f, frames))
            side = -1.f;
    }

    // Both tables are written once, complete and checked (writeFileAtomically), at the end.
    std::ostringstream csv;
    csv << "frame,x,y,z,psnr_nearest,psnr_engine,psnr_visibility,probes_engine,"
           "hidden_share,fallback_pixels,mirror_pixels,psnr_visibility_mirror_lookup\n";
    std::vector<double> mirrorLookupPsnr; // the visibility blend's mirror lookup vs the truth
    std::array<std::vector<double>, 3> psnr, overlapPsnr;
    std::array<double, 3> pop{}, popTruth{}, popExcess{};
    std::array<int, 3> popFrame{};
    std::optional<FrameImages> previous;
    std::vector<Image> worstTiles;
    std::vector<std::string> worstLabels;
    double worstEngine = 1e9;
    // Texture fetches per reflector pixel: [blend][K = 1, 2, 4]; and how often each case of
    // the visibility blend occurs.
    constexpr std::array<int, 3> kKs{1, 2, 4};
    std::array<std::array<double, 3>, 3> fetchSum{};
    double pixelSum = 0, lookupSum = 0, hiddenSum = 0, fallbackSum = 0, outsideSum = 0;
    int firstOutsideFrame = -1;
    long bestTimingScore = -1;
    int timingFrame = 0;
    ProgressBar bar("level walk " + fs::path(o.scene).filename().string());
    for (int f = 0; f < frames; ++f) {
        const auto [centre, tangent] = path.at(float(f) / float(frames - 1));
        roots.setOffset(scene.registry, centre - anchor);
        const CameraView camera = chaseCamera(centre, tangent, side, o.width, o.height);
        TraceOptions traceOptions = groundTruthOptions(scene, true);
        if (rough) {
            traceOptions.mirrorRoughness = [r = o.roughness, &maps](ecs::Entity e, glm::vec2 uv) {
                return maps.at(r, e, uv);
            };
            traceOptions.glossySamples = o.glossySamples;
        }
        const GroundTruthTracer tracer(scene.registry, traceOptions);
        FrameImages img;
        const GroundTruthImage truth = tracer.render(camera);
        img.truth = truth.color;
        img.mask = erodedMask(truth.mirrorMask);
        for (Image& b : img.blends)
            b = truth.color;
        Image mirrorLookup = truth.color;
        long evaluated = 0, hidden = 0, fallback = 0;
        const std::vector<ReflectorPixel> pixels =
            reflectorPixels(tracer, camera, truth.mirrorMask);
        const long mirrorPixels = long(pixels.size());
        for (const ReflectorPixel& px : pixels) {
            // The pixel's roughness, and the shader's GGX albedo with it (1 for a mirror).
            const float r = rough ? maps.at(o.roughness, px.entity, px.uv) : 0.f;
            const float albedo = r > 0.f ? ggxAlbedo(std::min(px.cosView(), 1.f), r) : 1.f;
            const glm::vec3 m =
                level.radiance(px.position, px.lhat, LevelBlend::Visibility, o.k, 0.f).radiance;
            std::copy(&m[0], &m[0] + 3, mirrorLookup.at(px.x, px.y));
            for (std::size_t b = 0; b < kBlends.size(); ++b) {
                const LevelSample s = level.radiance(px.position, px.lhat, kBlends[b], o.k, r);
                const glm::vec3 c = albedo * s.radiance;
                std::copy(&c[0], &c[0] + 3, img.blends[b].at(px.x, px.y));
                if (kBlends[b] == LevelBlend::Visibility) {
                    evaluated += long(s.weights.size()) + s.hidden;
                    hidden += s.hidden;
                    fallback += s.fallback && !s.outside ? 1 : 0;
                    outsideSum += s.outside ? 1 : 0;
                    if (s.outside && firstOutsideFrame < 0) firstOutsideFrame = f;
                }
                for (std::size_t k = 0; k < kKs.size(); ++k)
                    fetchSum[b][k] +=
                        kKs[k] == o.k
                            ? s.fetches
                            : level.radiance(px.position, px.lhat, kBlends[b], kKs[k], r).fetches;
            }
        }
        pixelSum += double(mirrorPixels);
        lookupSum += double(evaluated);
        hiddenSum += double(hidden);
        fallbackSum += double(fallback);
        const LevelSample atCentre =
            level.radiance(centre, glm::vec3(1, 0, 0), LevelBlend::Engine, o.k);
        const bool overlap = atCentre.weights.size() >= 2;
        result.overlapFrames += overlap ? 1 : 0;
        // The frame the GPU pass is timed at: where probes overlap, the most reflector pixels.
        const long timingScore = mirrorPixels + (overlap ? 1L << 40 : 0);
        if (timingScore > bestTimingScore) {
            bestTimingScore = timingScore;
            timingFrame = f;
        }
        csv << f << ',' << centre.x << ',' << centre.y << ',' << centre.z;
        for (std::size_t b = 0; b < kBlends.size(); ++b) {
            const ImageStats st = compareImages(img.blends[b], img.truth, &img.mask);
            const double p = framePsnr(st);
            psnr[b].push_back(p);
            if (overlap) overlapPsnr[b].push_back(p);
            csv << ',' << formatPsnr(p);
        }
        csv << ",\"" << weightsText(level, atCentre) << "\","
            << (evaluated ? double(hidden) / double(evaluated) : 0.0) << ',' << fallback << ','
            << mirrorPixels;
        {
            const ImageStats st = compareImages(mirrorLookup, img.truth, &img.mask);
            mirrorLookupPsnr.push_back(framePsnr(st));
            csv << ',' << formatPsnr(mirrorLookupPsnr.back()) << '\n';
        }
        if (previous) {
            const double truthChange =
                rmsChange(img.truth, previous->truth, img.mask, previous->mask);
            for (std::size_t b = 0; b < kBlends.size(); ++b) {
                const double change =
                    rmsChange(img.blends[b], previous->blends[b], img.mask, previous->mask);
                if (change > pop[b]) {
                    pop[b] = change;
                    popTruth[b] = truthChange;
                    popFrame[b] = f;
                }
                popExcess[b] = std::max(popExcess[b], change - truthChange);
            }
        }
        // The picture: the frame where engine-style blending is worst.
        // (A frame without a PSNR is drawn only when no frame has one.)
        if (worstTiles.empty() || psnr[1].back() < worstEngine) {
            worstEngine = std::isnan(psnr[1].back()) ? 1e9 : psnr[1].back();
            const std::string at = "frame " + std::to_string(f) + " ";
            worstTiles = {img.truth, img.blends[0], img.blends[1], img.blends[2], Image{}};
            worstLabels = {at + "truth", at + "nearest", at + "engine", at + "visibility", ""};
            for (std::size_t b = 0; b < kBlends.size(); ++b) {
                worstTiles.push_back(errorHeatmap(img.blends[b], img.truth, &img.mask, 0.25f));
                worstLabels.push_back(std::string("error ") + toString(kBlends[b]) + " " +
                                      formatPsnr(psnr[b].back()) + " dB");
            }
        }
        previous = std::move(img);
        if (o.progress) bar.update(double(f + 1) / frames);
    }
    if (o.timing) {
        const int f = timingFrame;
        const auto [centre, tangent] = path.at(float(f) / float(frames - 1));
        roots.setOffset(scene.registry, centre - anchor);
        const auto context = gpu::GlContext::createHeadless();
        result.passTimes = timeLevelPasses(reflectionScene, levelDir, settings,
                                           chaseCamera(centre, tangent, side, o.width, o.height),
                                           centre, o.roughness, result.timer);
        result.timedFrame = f;
    }
    roots.setOffset(scene.registry, glm::vec3(0.f));

    std::ostringstream summary;
    summary << "blend,psnr_mean,psnr_worst,overlap_psnr_mean,overlap_psnr_worst,pop_rms,"
               "truth_change_rms,pop_frame,pop_excess_rms\n";
    // Frames without a PSNR are left out of the means and worsts ("none" when no frame has
    // one), as every report of the tools has it.
    const auto cell = [](double v) {
        std::ostringstream c;
        if (std::isnan(v))
            c << "none";
        else
            c << v;
        return c.str();
    };
    for (std::size_t b = 0; b < kBlends.size(); ++b) {
        LevelWalkBlendSummary s;
        s.blend = toString(kBlends[b]);
        s.meanPsnr = meanPsnr(psnr[b]);
        s.worstPsnr = worstPsnr(psnr[b]);
        s.overlapMeanPsnr = meanPsnr(overlapPsnr[b]);
        s.overlapWorst = worstPsnr(overlapPsnr[b]);
        s.pop = pop[b];
        s.truthPop = popTruth[b];
        s.popExcess = popExcess[b];
        summary << s.blend << ',' << cell(s.meanPsnr) << ',' << cell(s.worstPsnr) << ','
                << cell(s.overlapMeanPsnr) << ',' << cell(s.overlapWorst) << ',' << s.pop << ','
                << s.truthPop << ',' << popFrame[b] << ',' << s.popExcess << '\n';
        log << std::left << std::setw(11) << s.blend << " PSNR mean " << formatPsnr(s.meanPsnr)
            << " worst " << formatPsnr(s.worstPsnr) << " | overlap frames mean "
            << formatPsnr(s.overlapMeanPsnr) << " worst " << formatPsnr(s.overlapWorst)
            << " | largest change " << s.pop << " RMS (truth " << s.truthPop
            << "), worst excess over truth " << s.popExcess << '\n';
        result.blends.push_back(s);
    }
    result.mirrorLookupMeanPsnr = meanPsnr(mirrorLookupPsnr);
    result.mirrorLookupWorstPsnr = worstPsnr(mirrorLookupPsnr);
    summary << "visibility (mirror lookup)," << cell(result.mirrorLookupMeanPsnr) << ','
            << cell(result.mirrorLookupWorstPsnr) << ",,,,,,\n";
    if (rough)
        log << "visibility with the mirror lookup (what a rough reflector drew before): PSNR mean "
            << formatPsnr(result.mirrorLookupMeanPsnr) << " worst "
            << formatPsnr(result.mirrorLookupWorstPsnr) << '\n';
    summary << "\nfetches_per_pixel,k=1,k=2,k=4\n";
    for (std::size_t b = 0; b < kBlends.size(); ++b) {
        summary << toString(kBlends[b]);
        log << "fetches per reflector pixel, " << toString(kBlends[b]) << ":";
        for (std::size_t k = 0; k < kKs.size(); ++k) {
            const double perPixel = pixelSum > 0 ? fetchSum[b][k] / pixelSum : 0.0;
            summary << ',' << perPixel;
            log << " K=" << kKs[k] << " " << perPixel;
            result.fetchesPerPixel[b][k] = perPixel;
        }
        summary << '\n';
        log << " (an envmap lookup: 1)\n";
    }
    result.hiddenShare = lookupSum > 0 ? hiddenSum / lookupSum : 0.0;
    result.fallbackShare = pixelSum > 0 ? fallbackSum / pixelSum : 0.0;
    result.outsideShare = pixelSum > 0 ? outsideSum / pixelSum : 0.0;
    summary << "\ncase,share\nprobe lookups hidden from their probe," << result.hiddenShare
            << "\npixels no probe with influence sees (engine blend instead),"
            << result.fallbackShare << "\npixels outside every influence (nearest probe),"
            << result.outsideShare << '\n';
    log << "visibility: " << 100.0 * result.hiddenShare << "% of probe lookups hidden, "
        << 100.0 * result.fallbackShare << "% of pixels seen by no probe (engine blend), "
        << 100.0 * result.outsideShare << "% outside every influence (nearest probe)\n";
    if (firstOutsideFrame >= 0)
        log << "warning: the reflector leaves every influence volume (first at frame "
            << firstOutsideFrame << "): the nearest probe answers there\n";
    if (!result.passTimes.empty()) {
        std::ostringstream timing;
        timing << "blend,k,ms_median,ratio_to_envmap,frames,walk_frame,timer\n";
        log << "reflector pass at frame " << result.timedFrame << " (" << result.timer << "):\n";
        for (const LevelPassTime& t : result.passTimes) {
            timing << t.blend << ',' << t.k << ',' << t.ms << ',' << t.ratioToEnvmap << ','
                   << t.frames << ',' << result.timedFrame << ",\"" << result.timer << "\"\n";
            log << "  " << std::left << std::setw(19) << t.blend << " K=" << t.k << "  "
                << std::fixed << std::setprecision(3) << t.ms << " ms  x" << std::setprecision(2)
                << t.ratioToEnvmap << std::defaultfloat << std::setprecision(6) << '\n';
        }
        writeFileAtomically((fs::path(o.out) / "timing.csv").string(), timing.str());
    }
    writeFileAtomically((fs::path(o.out) / "frames.csv").string(), csv.str());
    writeFileAtomically((fs::path(o.out) / "summary.csv").string(), summary.str());
    log << frames << " frames, " << result.overlapFrames
        << " with two or more probes at the reflector -> " << o.out << "/frames.csv\n";
    if (!worstTiles.empty())
        writeImage((fs::path(o.out) / "level_walk.png").string(),
                   contactSheet(worstTiles, worstLabels, 4, o.width));
    return result;
}

} // namespace sandbox
} // namespace specula
