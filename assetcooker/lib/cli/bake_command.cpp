#include "assetcooker/lib/cli/bake_command.h"

#include "assetcooker/lib/cli/bake_args.h"
#include "assetcooker/lib/cli/signal_guard.h"
#include "assetcooker/lib/cli/slurm_command.h"
#include "assetcooker/lib/os/output_lock.h"
#include "components/reflection_probe/writer/probe_folder.h"
#include "engine/core/error.h"
#include "engine/image_io/compare.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>

namespace specula::cook {

namespace {

constexpr const char* kBakeDescription =
    "Bakes the reflection probe of SCENE (.gltf/.glb) into DIR: manifest.json plus one KTX2\n"
    "cube map per layer (RGBA32F composite, RGBA16F object layers where every value fits a\n"
    "half; RGB radiance, A distance from the probe centre; docs/formats.md). Rays are traced\n"
    "with Embree on all cores.\n"
    "\n"
    "Probe placement: --probe, else the first node whose extras hold \"specula_probe\": {...}\n"
    "(members: cell_size), else the centre of the reflectors. Reflectors are the nodes with\n"
    "\"specula_reflector\": true or {\"f0\": F, \"roughness\": R or \"material\"}, and the meshes\n"
    "whose material has metallic >= 0.9 and roughness <= 0.1 (F0 its base colour's luminance;\n"
    "roughness per texel from its metallic-roughness texture) unless a node above says\n"
    "\"specula_reflector\": false; every other mesh is environment, one layer per root node\n"
    "unless grouped with \"specula_layer\": \"name\".\n"
    "\n"
    "lightfield (Yu et al. 2005): six slabs around a cubic cell of side L, camera planes on the\n"
    "cell faces extended to 3L, NUM x NUM cameras of RES x RES pixels (90 degree field of view)\n"
    "each; raw atlases (see lightfield_asset.h) and the focal-plane disparity per slab.\n"
    "\n"
    "pem (Hakura et al. 2001): one cube map of R x R x 6 per parameter sample t = k/N (the\n"
    "viewpoint on the walk's camera orbit, or the reflectors on a walk path), looked up through\n"
    "the environment's distance cube (--geometry distance) or its bounding box (box),\n"
    "each inferred by least squares from the ray-traced reflections (self- and\n"
    "inter-reflections included) of S x S rays per reflector pixel of a WxH camera image; one\n"
    "RGB32F KTX2 cube per sample. The bake measures its maps against the ray tracer at the "
    "samples\n"
    "and half-way between them and prints both PSNRs.\n"
    "The options of one flavour are refused with another.\n"
    "\n"
    "A level: when the scene has several \"specula_probe\" nodes, or --probe is given more\n"
    "than once, or --probes FILE, every probe is baked into DIR/<probe name>/ and DIR/level.json\n"
    "indexes them (position, proxy box, influence box or sphere, blend distance, priority,\n"
    "checksums). Probe members in the markup (boxes relative to the probe): \"proxy\": {\"min\",\n"
    "\"max\"}, \"influence\": {\"box\": {\"min\", \"max\"}} or {\"sphere\": {\"radius\"}},\n"
    "\"blend_distance\" (default 0.5 m), \"priority\" (0); the proxy defaults to the room the\n"
    "probe stands in (each side at the farthest wall plane a grid of rays over that cube face\n"
    "ends on, never nearer than the axis ray), the influence to the proxy grown by the blend\n"
    "distance and cut half-way to other probes inside it. A re-run re-bakes only\n"
    "the probes whose geometry in reach, options or sky changed, and says which and why.\n"
    "\n"
    "A level's bake options can live in a file beside the scene: --config FILE (TOML or INI)\n"
    "with a [bake] section, e.g. face-res = 128; flags on the command line win.\n"
    "\n"
    "--slurm bakes a level, or a PEM's samples, on a Slurm cluster: a job array of\n"
    "`specula-cook bake-shard` over the leaf shards DIR/.shards lacks (distance probes,\n"
    "light-field parts, PEM traces), a second array over the shards that depend on them\n"
    "(light-field probes, PEM sample maps) and `specula-cook merge`, each after the one before\n"
    "succeeded (--dependency=afterok), with a progress bar; failed shards are resubmitted\n"
    "(--retries) and then reported by index and reason. DIR must be a folder shared by every\n"
    "node (same path everywhere), as must SCENE and this executable. The result is the plain\n"
    "bake's, byte for byte: a level in DIR, a PEM in DIR/pem/ (DIR holds the shard store).\n";

constexpr const char* kBakeFooter =
    "Signals: SIGINT/SIGTERM at any moment before the final rename leave DIR as it was and\n"
    "no temporary folder behind. DIR is replaced only if it is empty or a cooked probe that\n"
    "holds nothing but the files its manifest lists, and never if it holds SCENE. Temporary\n"
    "folders of killed bakes (DIR.tmp-PID of a process that no longer runs) are removed.\n"
    "\n"
    "One writer at a time: a bake holds the lock file DIR.lock (beside DIR, naming its host\n"
    "and process) for its whole run; a second bake, shards, merge or bake-shard of DIR fails\n"
    "at once, naming the holder.\n"
    "\n"
    "exit status: 0 ok, 1 the scene could not be baked, 2 bad command line, 130 cancelled\n"
    "by SIGINT/SIGTERM (DIR left as it was)\n";

void printLightFieldSummary(const CookOptions& a, const CookResult& r, double seconds,
                            std::ostream& out) {
    const auto& asset = std::get<LightFieldAsset>(r.asset);
    const auto& settings = std::get<LightFieldCookSettings>(a.flavour);
    out << "baked light field: 6 slabs x " << settings.cameras << "^2 cameras x "
        << settings.imageRes << "^2 px, cell " << r.cellSize << " m, "
        << toString(asset.compression) << ", " << asset.diskBytes() << " bytes on disk, "
        << asset.gpuBytes() << " bytes of GPU memory, bake " << r.bakeSeconds << " s, total "
        << seconds << " s -> " << a.out << "/manifest.json\n";
    for (int k = 0; k < 6; ++k) {
        const LightFieldSlab& s = asset.slabs[std::size_t(k)];
        out << "  slab " << slabName(k) << ": depth " << s.nearDepth << " .. " << s.farDepth
            << " m, sky " << s.skyFraction << ", focal depth " << s.focalDepth << " m, disparity "
            << s.disparity << " px/camera\n";
    }
    for (const LightFieldIntrusion& i : asset.intrusions)
        out << (i.region == "cell" ? "  warning: " : "  note: ") << i.object << " lies in "
            << i.region << (i.region == "cell" ? " (reaches " : " (gap to the cell ")
            << std::abs(i.depth) << " m)"
            << (i.region == "cell" ? ": reflectors there see it wrongly; shrink the cell\n"
                                   : ": baked from where each line leaves the cell, so "
                                     "reflectors inside the cell still see it right\n");
    for (const ReflectorOverhang& o : r.overhangs)
        out << "  warning: reflector " << o.node << " reaches " << o.metres
            << " m outside the cell (--cell-size " << r.cellSize + 2.f * o.metres
            << " would hold it)\n";
}

void printDistanceSummary(const CookOptions& a, const CookResult& r, double seconds,
                          std::ostream& out) {
    const GlossyBake glossy = std::get<DistanceCookSettings>(a.flavour).glossy;
    const auto& asset = std::get<DistanceProbeAsset>(r.asset);
    out << "baked " << asset.layers.size() << " layers (" << asset.objectLayerCount()
        << " objects + composite) at " << asset.faceRes << "^2 x 6 in " << seconds << " s -> "
        << a.out << "/manifest.json\n";
    // The figures of the goal: the prefilter against the mirror bake's own time.
    out << "  plan + trace " << r.bakeSeconds << " s; glossy: ";
    if (!asset.glossyLevels.empty())
        out << asset.glossyLevels.size() << " GGX levels of the composite ("
            << asset.glossyLevels.front()[0].width << "^2 .. " << asset.glossyLevels.back()[0].width
            << "^2 x 6), prefilter " << r.prefilterSeconds << " s\n";
    else
        out << "none (--glossy " << toString(glossy)
            << (glossy == GlossyBake::Auto ? ": every reflector is a mirror" : "") << ")\n";
    for (std::size_t i = 0; i < asset.layers.size(); ++i) {
        const DistanceProbeLayer& L = asset.layers[i];
        out << "  layer " << i << " " << L.name << ": d-bar " << L.avgDistance << " m, "
            << L.solidAngle << " sr, " << L.method << "\n";
    }
}

void printPemSummary(const CookOptions& a, const CookResult& r, double seconds, std::ostream& out) {
    const auto& asset = std::get<PemAsset>(r.asset);
    const glm::vec3 box = asset.boxMax - asset.boxMin;
    out << "baked " << asset.samples.size() << " parameterized environment maps ("
        << asset.parameterKind << " along " << asset.path << ") at " << asset.faceRes
        << "^2 x 6, box " << box.x << " x " << box.y << " x " << box.z << " m, bake "
        << r.bakeSeconds << " s, total " << seconds << " s -> " << a.out << "/manifest.json\n";
    if (r.pemFits.empty()) return;
    // The cooker's own measurement against the ray tracer: what the maps are worth on the
    // baked viewpoints and half-way between them, where the runtime blends two. A sample
    // without a PSNR (nothing measured, or an open path's last sample: nothing lies past it)
    // is left out of the means; "none" when no sample has one.
    std::vector<double> on, off;
    double infer = 0, worstInfer = 0, rays = 0, copies = 0;
    std::string leftOut; // the samples whose view held no reflector pixel
    for (const PemSampleFit& f : r.pemFits) {
        if (f.leftOut) leftOut += (leftOut.empty() ? "" : ", ") + std::to_string(f.parameter);
        on.push_back(f.psnrOn), off.push_back(f.psnrOff);
        infer += f.inferSeconds, rays += f.rays;
        copies += f.roundingRows;
        worstInfer = std::max(worstInfer, f.inferSeconds);
    }
    if (!leftOut.empty())
        out << "left out " << r.pemFits.size() - asset.samples.size() << " of " << r.pemFits.size()
            << " samples (no reflector pixel in view) at t = " << leftOut << "\n";
    const double n = double(asset.samples.size());
    char line[320];
    std::snprintf(
        line, sizeof line,
        "fit against the ray tracer (%.0f reflector rays a sample, no Fresnel): on the samples "
        "%s dB, half-way between them %s dB (worst %s); inference %.2f s per sample "
        "(worst %.2f); rows where the display's rounding reaches (--rounding-reach) for "
        "%.1f%% of the rays\n",
        rays / n, formatPsnr(meanPsnr(on), 1).c_str(), formatPsnr(meanPsnr(off), 1).c_str(),
        formatPsnr(worstPsnr(off), 1).c_str(), infer / n, worstInfer,
        rays > 0 ? 100.0 * copies / rays : 0.0);
    out << line;
}

void printLevelSummary(const LevelCookResult& r, std::ostream& out) {
    std::size_t baked = 0;
    double bakeSeconds = 0;
    for (const LevelProbeOutcome& p : r.probes)
        if (p.baked) ++baked, bakeSeconds += p.seconds;
    out << "level: " << r.probes.size() << " probes, " << baked << " baked (" << bakeSeconds
        << " s";
    if (baked > 0) out << ", " << bakeSeconds / double(baked) << " s per probe";
    out << "), " << r.probes.size() - baked << " up to date, total " << r.seconds << " s -> "
        << r.index << "\n";
}

int runBake(const BakeArgs& a, const SlurmArgs& s, std::ostream& out) {
    if (s.slurm) return runSlurmBake(a, s, out);
    const bool lightField = a.flavour == "lightfield";
    const CookOptions options = checkedCookOptions(a);
    const SignalGuard guard; // first: a signal during the load and the plan is honoured too
    const OutputLock lock(options.out, "bake", FileLockMode::Exclusive); // one writer: fails now
    const auto start = std::chrono::steady_clock::now();
    ProbeScene scene(options.scene, options.sky);
    throwIfCancelled(options.out);
    if (isLevel(a, scene)) {
        printLevelSummary(cookLevel(scene, levelCookOptions(a, options, scene), &out), out);
        return cli::kExitOk;
    }
    const CookResult r = cookProbe(scene, options, &out);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (lightField)
        printLightFieldSummary(options, r, seconds, out);
    else if (a.flavour == "pem")
        printPemSummary(options, r, seconds, out);
    else
        printDistanceSummary(options, r, seconds, out);
    return cli::kExitOk;
}

} // namespace

void addBakeCommand(cli::ToolCli& tool) {
    auto a = std::make_shared<BakeArgs>();
    auto s = std::make_shared<SlurmArgs>();
    CLI::App* sub = tool.addSubcommand(
        "bake", "bake a scene's reflection probe into a cooked folder", kBakeDescription,
        kBakeFooter, [a, s](std::ostream& out) { return runBake(*a, *s, out); });
    addBakeOptions(tool, sub, *a);
    addSlurmOptions(sub, *s);
}

} // namespace specula::cook
