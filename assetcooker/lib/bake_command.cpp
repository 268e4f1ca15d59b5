#include "bake_command.h"

#include "assetcooker/lib/cli.h"
#include "assetcooker/lib/distance_bake.h"
#include "assetcooker/lib/effect_plan.h"
#include "assetcooker/lib/lightfield_bake.h"
#include "components/reflection_probe/probe_folder.h"
#include "components/reflection_probe/scene_markup.h"
#include "engine/core/error.h"
#include "engine/core/flags.h"
#include "engine/core/progress.h"
#include "engine/image/image_io.h"
#include "engine/scene/gltf_loader.h"

#include <chrono>
#include <csignal>
#include <filesystem>

namespace specula::cook {

const std::string_view kBakeUsage =
    "usage: specula-cook bake SCENE --out DIR [--flavour distance|lightfield] [options]\n"
    "\n"
    "Bakes the reflection probe of SCENE (.gltf/.glb) into DIR: manifest.json plus one float\n"
    "EXR cube map per layer (N x 6N, faces +X -X +Y -Y +Z -Z top to bottom; RGB radiance, A\n"
    "distance from the probe centre). Rays are traced with Embree on all cores.\n"
    "\n"
    "Probe placement: --probe, else the first node whose extras hold \"specula_probe\": {...}\n"
    "(members: cell_size), else the centre of the reflectors. Reflectors are the nodes with\n"
    "\"specula_reflector\": true or {\"f0\": F}; every other mesh is environment, one layer\n"
    "per root node unless grouped with \"specula_layer\": \"name\".\n"
    "\n"
    "options:\n"
    "  --out DIR          output folder (replaced atomically; never left half-written)\n"
    "  --flavour F        distance (default) or lightfield\n"
    "  --face-res N       cube face resolution, 1..4096 (default 256)\n"
    "  --probe x,y,z      probe centre in world space (overrides the markup)\n"
    "  --sky FILE         equirectangular panorama for the distant environment (default: black)\n"
    "  --layers L         plan (default): the layers and methods of the effect plan\n"
    "                     (specula-cook plan); objects: one layer per object\n"
    "  -h, --help         show this help\n"
    "\n"
    "lightfield (Yu et al. 2005): six slabs around a cubic cell of side L, camera planes on the\n"
    "cell faces extended to 3L, NUM x NUM cameras of RES x RES pixels (90 degree field of view)\n"
    "each; raw atlases (see lightfield_asset.h) and the focal-plane disparity per slab.\n"
    "  --cell-size L      cell side in metres (default: the probe's cell_size, else 1.5)\n"
    "  --cell-center x,y,z  cell centre in world space (default: the probe position)\n"
    "  --cameras NUM      cameras per side of a slab, 2..256 (default 8)\n"
    "  --image-res RES    pixels per side of a camera image, a multiple of 4 (default 64)\n"
    "  --compress C       none (sRGB RGB8, default) or bc1 (DXT1); bc7 is not supported\n"
    "\n"
    "Signals: SIGINT/SIGTERM at any moment before the final rename leave DIR as it was and\n"
    "no temporary folder behind. DIR is replaced only if it is empty or a cooked probe that\n"
    "holds nothing but the files its manifest lists, and never if it holds SCENE. Temporary\n"
    "folders of killed bakes (DIR.tmp-PID of a process that no longer runs) are removed.\n"
    "\n"
    "exit status: 0 ok, 1 the scene could not be baked, 2 bad command line, 130 cancelled\n"
    "by SIGINT/SIGTERM (DIR left as it was)\n";

namespace {
extern "C" void onSignal(int) {
    requestCancel();
}

// SIGINT/SIGTERM anywhere in a bake (load, plan, trace, write) only request a cancel: the
// bake stops at its next check and throws Cancelled, and DIR stays as it was unless the
// final rename already happened.
struct SignalGuard {
    using Handler = void (*)(int);
    Handler oldInt, oldTerm;
    SignalGuard() {
        clearCancelRequest();
        oldInt = std::signal(SIGINT, onSignal);
        oldTerm = std::signal(SIGTERM, onSignal);
    }
    ~SignalGuard() {
        std::signal(SIGINT, oldInt);
        std::signal(SIGTERM, oldTerm);
    }
};

// Before any work: repair what killed bakes left beside DIR (a line each on `out`), and
// refuse a DIR that may not be replaced now rather than after a long bake.
void prepareOutput(const std::string& dir, const std::string& scene, std::ostream& out) {
    removeStaleProbeTemporaries(dir, out);
    checkProbeFolderReplaceable(dir, scene);
}

// Runs a baker. Polled cancelled, the bakers stop with a plain Error ("bake: cancelled");
// reported as the cancel it is, naming DIR.
template <class Bake> auto bakeUnlessCancelled(const std::string& dir, Bake&& bake) {
    try {
        return bake();
    } catch (const Error&) {
        throwIfCancelled(dir);
        throw;
    }
}

// What both flavours load: the scene, its markup and the optional sky panorama.
struct BakeInput {
    ecs::Registry registry;
    LoadedScene scene;
    SceneMarkup markup;
    Image sky;
    BakeInput(const std::string& scenePath, const std::optional<std::string>& skyPath)
        : scene(loadGltf(scenePath, registry)), markup(readSceneMarkup(registry, scene, scenePath)),
          sky(skyPath ? readImage(*skyPath) : Image()) {}
};

// `bake --flavour lightfield`: the remaining flags, the bake on all cores with a progress
// bar, the same cancel checks and atomic write as the distance flavour.
int runLightFieldBake(Flags& flags, const std::optional<std::string>& outDir,
                      const std::optional<glm::vec3>& probeAt,
                      const std::optional<std::string>& skyPath, std::ostream& out) {
    const auto cellSize = flags.value("--cell-size");
    const auto cellCentre = flags.vec3Value("--cell-center");
    const int cameras = flags.intValue("--cameras", 8, 2, 256);
    const int res = flags.intValue("--image-res", 64, 4, 4096);
    const std::string compress = flags.value("--compress").value_or("none");
    const auto pos = flags.positionals();
    if (pos.size() != 1) throw UsageError{"bake needs exactly one SCENE"};
    if (!outDir || outDir->empty()) throw UsageError{"bake needs --out DIR"};
    if (compress == "bc7")
        throw UsageError{"--compress: bc7 is not supported by this cooker (no BC7 encoder); "
                         "use bc1 or none"};
    if (compress != "none" && compress != "bc1")
        throw UsageError{"--compress: expected none or bc1, got '" + compress + "'"};
    if (res % 4 != 0) throw UsageError{"--image-res: expected a multiple of 4 (BC1 blocks)"};
    if (cameras * res > 16384)
        throw UsageError{"--cameras x --image-res must be at most 16384 (the 2D texture side)"};

    prepareOutput(*outDir, pos[0], out);
    const auto start = std::chrono::steady_clock::now();
    BakeInput in(pos[0], skyPath);
    throwIfCancelled(*outDir);

    LightFieldBakeOptions o;
    o.cellCentre = cellCentre ? *cellCentre
                   : probeAt  ? *probeAt
                              : markupProbeCentre(in.registry, in.markup, in.scene);
    o.cellSize =
        cellSize ? parseFloat("--cell-size", *cellSize, 1e-3f, 1e4f) : markupCellSize(in.markup);
    o.cameras = cameras;
    o.res = res;
    o.compression = compress == "bc1" ? LightFieldCompression::BC1 : LightFieldCompression::None;
    o.sky = in.sky.empty() ? nullptr : &in.sky;
    o.cancelled = [] { return cancelRequested(); };
    std::vector<std::string> warnings; // the probe placement's (checkProbePlacement)
    o.warnings = &warnings;
    LightFieldAsset asset;
    {
        ProgressBar bar("baking light field " + std::filesystem::path(pos[0]).filename().string());
        o.progress = [&](double f) { bar.update(f); };
        asset = bakeUnlessCancelled(*outDir,
                                    [&] { return bakeLightFieldProbe(in.registry, in.markup, o); });
    }
    for (const std::string& w : warnings)
        out << "  warning: " << w << '\n';
    throwIfCancelled(*outDir);
    writeLightFieldProbe(asset, *outDir, pos[0]);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    out << "baked light field: 6 slabs x " << cameras << "^2 cameras x " << res << "^2 px, cell "
        << o.cellSize << " m, " << toString(o.compression) << ", " << asset.diskBytes()
        << " bytes on disk, " << asset.gpuBytes() << " bytes of GPU memory, bake "
        << asset.bakeSeconds << " s, total " << seconds << " s -> " << *outDir
        << "/manifest.json\n";
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
    for (const ReflectorOverhang& r :
         findReflectorOverhangs(in.registry, in.markup, o.cellCentre, o.cellSize))
        out << "  warning: reflector " << r.node << " reaches " << r.metres
            << " m outside the cell (--cell-size " << o.cellSize + 2.f * r.metres
            << " would hold it)\n";
    return kExitOk;
}
} // namespace

int runBake(std::span<const std::string> args, std::ostream& out, std::ostream& err) {
    const SignalGuard guard; // first: a signal during the load and the plan is honoured too
    Flags flags(args);
    const auto outDir = flags.value("--out");
    const std::string flavour = flags.value("--flavour").value_or("distance");
    const int faceRes = flags.intValue("--face-res", 256, 1, 4096);
    const auto probeAt = flags.vec3Value("--probe");
    const auto skyPath = flags.value("--sky");
    const std::string layers = flags.value("--layers").value_or("plan");
    if (flavour == "lightfield") return runLightFieldBake(flags, outDir, probeAt, skyPath, out);
    const auto pos = flags.positionals();
    if (pos.size() != 1) throw UsageError{"bake needs exactly one SCENE"};
    if (!outDir || outDir->empty()) throw UsageError{"bake needs --out DIR"};
    if (layers != "plan" && layers != "objects")
        throw UsageError{"--layers: expected 'plan' or 'objects', got '" + layers + "'"};
    if (flavour != "distance")
        throw UsageError{"--flavour: expected 'distance' or 'lightfield', got '" + flavour + "'"};

    prepareOutput(*outDir, pos[0], out);
    const auto start = std::chrono::steady_clock::now();
    BakeInput in(pos[0], skyPath);
    throwIfCancelled(*outDir);

    DistanceBakeOptions o;
    o.centre = probeAt ? *probeAt : markupProbeCentre(in.registry, in.markup, in.scene);
    o.faceRes = faceRes;
    o.sky = in.sky.empty() ? nullptr : &in.sky;
    o.reflectorReach =
        markupReflectorReach(in.registry, in.markup, o.centre, markupCellSize(in.markup));
    const EffectPlan plan = planEffects(in.registry, in.markup, o.centre, o.reflectorReach);
    if (layers == "plan") applyPlan(plan, o);
    throwIfCancelled(*outDir);
    o.cancelled = [] { return cancelRequested(); };
    std::vector<std::string> warnings; // the probe placement's (checkProbePlacement)
    o.warnings = &warnings;
    DistanceProbeAsset asset;
    {
        ProgressBar bar("baking " + std::filesystem::path(pos[0]).filename().string());
        o.progress = [&](double f) { bar.update(f); };
        asset = bakeUnlessCancelled(*outDir,
                                    [&] { return bakeDistanceProbe(in.registry, in.markup, o); });
    }
    for (const std::string& w : warnings)
        out << "  warning: " << w << '\n';
    throwIfCancelled(*outDir);
    asset.effectPlan = plan.toJson().dump();
    writeDistanceProbe(asset, *outDir, pos[0]);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    out << "baked " << asset.layers.size() << " layers (" << asset.objectLayerCount()
        << " objects + composite) at " << faceRes << "^2 x 6 in " << seconds << " s -> " << *outDir
        << "/manifest.json\n";
    for (std::size_t i = 0; i < asset.layers.size(); ++i) {
        const DistanceProbeLayer& L = asset.layers[i];
        out << "  layer " << i << " " << L.name << ": d-bar " << L.avgDistance << " m, "
            << L.solidAngle << " sr, " << L.method << "\n";
    }
    (void)err;
    return kExitOk;
}

} // namespace specula::cook
