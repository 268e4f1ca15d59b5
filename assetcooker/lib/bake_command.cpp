#include "bake_command.h"

#include "assetcooker/lib/cli.h"
#include "assetcooker/lib/distance_bake.h"
#include "components/reflection_probe/scene_markup.h"
#include "engine/core/error.h"
#include "engine/core/flags.h"
#include "engine/core/progress.h"
#include "engine/image/image_io.h"
#include "engine/scene/gltf_loader.h"

#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>

namespace specula::cook {

const std::string_view kBakeUsage =
    "usage: specula-cook bake SCENE --out DIR [--flavour distance] [options]\n"
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
    "  --flavour F        distance (default)\n"
    "  --face-res N       cube face resolution, 1..4096 (default 256)\n"
    "  --probe x,y,z      probe centre in world space (overrides the markup)\n"
    "  --sky FILE         equirectangular panorama for the distant environment (default: black)\n"
    "  -h, --help         show this help\n"
    "\n"
    "exit status: 0 ok, 1 the scene could not be baked, 2 bad command line\n";

namespace {
std::atomic<bool> gInterrupted{false};
extern "C" void onSignal(int) { gInterrupted = true; }

// SIGINT/SIGTERM during a bake: stop at the next row, write nothing, leave DIR as it was.
struct SignalGuard {
    using Handler = void (*)(int);
    Handler oldInt, oldTerm;
    SignalGuard() {
        gInterrupted = false;
        oldInt = std::signal(SIGINT, onSignal);
        oldTerm = std::signal(SIGTERM, onSignal);
    }
    ~SignalGuard() {
        std::signal(SIGINT, oldInt);
        std::signal(SIGTERM, oldTerm);
    }
};
} // namespace

int runBake(std::span<const std::string> args, std::ostream& out, std::ostream& err) {
    Flags flags(args);
    const auto outDir = flags.value("--out");
    const std::string flavour = flags.value("--flavour").value_or("distance");
    const int faceRes = flags.intValue("--face-res", 256, 1, 4096);
    const auto probeAt = flags.vec3Value("--probe");
    const auto skyPath = flags.value("--sky");
    const auto pos = flags.positionals();
    if (pos.size() != 1) throw UsageError{"bake needs exactly one SCENE"};
    if (!outDir || outDir->empty()) throw UsageError{"bake needs --out DIR"};
    if (flavour != "distance")
        throw UsageError{"--flavour: expected 'distance', got '" + flavour + "'"};

    const auto start = std::chrono::steady_clock::now();
    ecs::Registry registry;
    const LoadedScene scene = loadGltf(pos[0], registry);
    const SceneMarkup markup = readSceneMarkup(registry, scene, pos[0]);
    Image sky;
    if (skyPath) sky = readImage(*skyPath);

    DistanceBakeOptions o;
    o.centre = probeAt ? *probeAt : markupProbeCentre(registry, markup, scene);
    o.faceRes = faceRes;
    o.sky = sky.empty() ? nullptr : &sky;
    o.reflectorReach = markupReflectorReach(registry, markup, o.centre, markupCellSize(markup));
    SignalGuard guard;
    o.cancelled = [] { return gInterrupted.load(); };
    DistanceProbeAsset asset;
    {
        ProgressBar bar("baking " + std::filesystem::path(pos[0]).filename().string());
        o.progress = [&](double f) { bar.update(f); };
        asset = bakeDistanceProbe(registry, markup, o);
    }
    if (gInterrupted) throw Error(*outDir, "", "interrupted; nothing was written");
    writeDistanceProbe(asset, *outDir, pos[0]);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    out << "baked " << asset.layers.size() << " layers (" << asset.objectLayerCount()
        << " objects + composite) at " << faceRes << "^2 x 6 in " << seconds << " s -> "
        << *outDir << "/manifest.json\n";
    for (std::size_t i = 0; i < asset.layers.size(); ++i) {
        const DistanceProbeLayer& L = asset.layers[i];
        out << "  layer " << i << " " << L.name << ": d-bar " << L.avgDistance << " m, "
            << L.solidAngle << " sr, " << L.method << "\n";
    }
    (void)err;
    return kExitOk;
}

} // namespace specula::cook
