#include "sandbox/lib/cli/sandbox_cli.h"

#include "assetcooker/lib/cli/tool_cli.h"
#include "engine/core/error.h"
#include "engine/core/file_write.h"
#include "sandbox/lib/bench/bench.h"
#include "sandbox/lib/bench/bench_methods.h"
#include "sandbox/lib/bench/glossy_bench.h"
#include "sandbox/lib/cli/added_reflector_flag.h"
#include "sandbox/lib/cli/created_output_folder.h"
#include "sandbox/lib/flavours/distance/host_timing.h"
#include "sandbox/lib/flavours/distance/level_walk.h"
#include "sandbox/lib/walk/walk.h"

#include <exception>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <regex>
#include <vector>

namespace specula::sandbox {

namespace {

constexpr const char* kOutputAndExitNote =
    "Every write is checked: a full disk or a short write fails the run (exit 1), and a\n"
    "failed run removes the --out folder again if it created it.\n"
    "\n"
    "exit status: 0 ok, 1 the input could not be processed, 2 bad command line\n";

constexpr const char* kWalkDescription =
    "Moves the reflectors along a path inside the probe's cell while the camera swings around\n"
    "them, and draws every frame with the chosen method. MANIFEST_OR_SCENE is a cooked probe\n"
    "(manifest.json; its scene is the manifest's \"source\" unless --scene is given) or a\n"
    "scene (.gltf/.glb), whose distance probe is baked first.\n"
    "\n"
    "Headless (--headless) it writes DIR/frame_NNNN.png, DIR/contact_sheet.png and\n"
    "DIR/frames.csv (frame, reflector position, camera angle, reflector-pass ms, and with\n"
    "--compare the PSNR against that frame's ground truth). Otherwise it opens a window\n"
    "(GLFW; runs under Xvfb): drag to orbit, wheel to zoom, WASD/arrows and Q/E move the\n"
    "reflector, space plays the path; a Dear ImGui panel switches the method, d_e, the layer\n"
    "method and (light field) the disparity, and shows the pass time and the current error.\n"
    "\n"
    "--roughness R draws every reflector rough (GGX, alpha = R^2; a reflector with a roughness\n"
    "map reads R times the map): the distance and light-field probes read their glossy chains,\n"
    "and --compare traces the GGX truth (--samples a pixel). Without it each reflector keeps\n"
    "its own roughness (markup or material), and the truth follows it.\n";

constexpr const char* kBenchDescription =
    "Sweeps every method and its accuracy parameters (d_e in {0.1, 0.03, 0.01, 0.003}; quick:\n"
    "{0.1, 0.01}) on each scene (default: the bundled room, truck_room, bowl_room and\n"
    "sky_only), and measures per\n"
    "row: median reflector-pass time (GL timer queries on a GPU; wall clock around glFinish on\n"
    "CPU renderers such as llvmpipe, whose queries miss deferred rasterisation; as many frames\n"
    "as a stable median needs), its ratio to envmap in the same run, RMSE and PSNR against the "
    "Embree ground truth\n"
    "on reflector pixels (environment-only and full), texture fetches per pixel (CPU twin),\n"
    "probe GPU memory and bake time. The ground truth itself is a row. The PEM rows (one PEM\n"
    "per N in {4, 8, 16, 32} viewpoints, quick: 8; faces as --face-res, at most 256; each\n"
    "inferred for the frame size) are drawn from the walk orbit's camera at a sample (t=on)\n"
    "and half-way between two (t=off), each against the ground truth of that camera, and\n"
    "the best single-bounce method (layered, else bisection, d_e 0.01) beside them from the\n"
    "same cameras (params '... pem-camera N=.. t=on|off'). The first N is also baked with every\n"
    "MIP level inferred (rows 'mip') and drawn with its level-0 maps' box-filtered chain\n"
    "(rows 'filtered-mip'); the log compares the three.\n"
    "\n"
    "Writes DIR/bench.csv, DIR/bench.md (machine and renderer named), DIR/accuracy_vs_time.png\n"
    "(PSNR against time, one line per method, Pareto front ringed), DIR/strip_<scene>.png\n"
    "(ground truth | envmap | boxproj | distance cubemap | light field, error maps below) and\n"
    "DIR/pem_<scene>.png (full truth | PEM at a sample and half-way, error maps below).\n";

// What walk's flags set; --size and --frames are resolved once the mode is known.
struct WalkArgs {
    WalkOptions o;
    std::string path = "orbit", size, parameter = "viewpoint";
    std::optional<int> frames;
    std::vector<std::string> addedReflectors;
};

int runWalk(WalkArgs& a, std::ostream& out) {
    WalkOptions& o = a.o;
    o.addedReflectors = parseAddedReflectors(a.addedReflectors);
    // The window walk opens its scene itself: it sees the reflectors through the scope.
    const AddedReflectorsScope added(o.addedReflectors);
    o.cameraPath = a.path == kCameraPathName;
    if (!o.cameraPath) parseWalkPath(a.path, o.path);
    o.pemByReflector = a.parameter == "reflector";
    if (o.cameraPath && o.pemByReflector)
        throw UsageError("--path", "camera moves the viewpoint; --parameter reflector walks the "
                                   "reflectors along orbit, line or figure8");
    if (!a.size.empty()) cli::parseSize(a.size, o.width, o.height);
    if (o.headless && a.frames && *a.frames < 1)
        throw UsageError("--frames", "expected at least 1 frame with --headless, got " +
                                         std::to_string(*a.frames));
    o.frames = a.frames.value_or(o.headless ? 60 : 0);
    if (o.compare && !o.headless) throw UsageError("--compare", "needs --headless");
    CreatedOutputFolder created(o.outDir);
    const int status = o.headless ? runWalkHeadless(o, out) : runWalkWindow(o, out);
    if (status == cli::kExitOk) created.keep();
    return status;
}

void addWalkCommand(cli::ToolCli& tool) {
    auto a = std::make_shared<WalkArgs>();
    WalkOptions& o = a->o;
    CLI::App* sub = tool.addSubcommand(
        "walk", "walk the reflectors through a scene (window, or frames to disk)", kWalkDescription,
        kOutputAndExitNote, [a](std::ostream& out) { return runWalk(*a, out); });
    sub->add_option("MANIFEST_OR_SCENE", o.input, "a cooked manifest.json or a .gltf/.glb scene")
        ->required();
    std::vector<std::string> methods; // the flavours' method tables, in order
    std::string methodHelp = "how reflections are looked up:";
    for (const MethodLabel& m : sandboxMethods()) {
        methods.push_back(m.name);
        methodHelp += std::string("\n  ") + m.name + ": " + m.help;
    }
    methodHelp += "\n(lightfield and pem bake their flavour's probe from a scene, pem for the "
                  "frame size with its parameter following the walk (--parameter); a "
                  "light-field or pem manifest always draws with its flavour)";
    sub->add_option("--method", o.method, methodHelp)->check(CLI::IsMember(methods));
    sub->add_option("--de", o.tolerance, "rectification tolerance d_e in metres")
        ->check(cli::finiteRange(1e-5, 10.0));
    sub->add_option("--path", a->path,
                    "the reflectors' path, within 0.2 cell sizes of the start; camera: the "
                    "camera follows the scene camera's glTF animation instead, first key to "
                    "last, past still reflectors (a PEM baked here is baked along it)")
        ->check(CLI::IsMember({"orbit", "line", "figure8", "camera"}));
    sub->add_option("--parameter", a->parameter,
                    "a PEM baked from a scene varies with the viewpoint (the camera swings, the "
                    "reflectors stay) or the reflector (the reflectors walk --path before a "
                    "still camera); a PEM manifest says which itself")
        ->check(CLI::IsMember({"viewpoint", "reflector"}));
    sub->add_option("--frames", a->frames,
                    "headless: frames to write (default 60); window: quit after N frames and "
                    "play the path (default: run until closed)")
        ->check(CLI::Range(0, 100000));
    sub->add_flag("--headless", o.headless, "no window: write frames to --out");
    sub->add_flag("--compare", o.compare,
                  "headless: trace every frame's ground truth and add its PSNR");
    sub->add_option("--out", o.outDir, "output folder")->check(cli::nonEmpty("a folder"));
    sub->add_option("--size", a->size, "frame size (default 640x480)")->check(cli::sizeText());
    sub->add_option("--scene", o.scene, "the scene of a manifest (overrides its \"source\")");
    sub->add_flag("--allow-stale", o.allowStale,
                  "walk a manifest whose recorded inputs differ from the scene's (other "
                  "meshes, materials, reflectors or --sky) with a warning each, instead of "
                  "refusing it");
    tool.allowEmpty(sub->add_option(
        "--sky", o.sky, "equirectangular panorama (default: the bundled field.jpg; '': black)"));
    sub->add_option("--face-res", o.faceRes, "cube face resolution when baking a scene")
        ->check(CLI::Range(8, 2048));
    sub->add_option("--roughness", o.roughness,
                    "every reflector's perceptual GGX roughness, 0 .. 1 (times its roughness map "
                    "where it has one; default: each reflector's own)")
        ->check(cli::finiteRange(0.0, 1.0));
    sub->add_option("--samples", o.glossySamples,
                    "GGX samples a pixel of the --compare truth where a reflector is rough "
                    "(default 256)")
        ->check(CLI::Range(1, 65536));
    addReflectorOption(sub, a->addedReflectors);
}

struct BenchArgs {
    BenchOptions o;
    std::string size;
    std::optional<int> faceRes, maxFrames;
    std::vector<std::string> addedReflectors;
    std::string pemNonNegative = "on";
};

int runBenchCommand(BenchArgs& a, std::ostream& out) {
    BenchOptions& o = a.o;
    o.addedReflectors = parseAddedReflectors(a.addedReflectors);
    if (!a.size.empty()) cli::parseSize(a.size, o.width, o.height);
    o.faceRes = a.faceRes.value_or(0);
    o.maxFrames = a.maxFrames.value_or(0);
    o.pemNonNegative = a.pemNonNegative == "on";
    CreatedOutputFolder created(o.outDir);
    const BenchReport r = runBench(o, out);
    created.keep();
    out << "wrote " << r.rows.size() << " rows to " << o.outDir << "/bench.csv, bench.md, "
        << "accuracy_vs_time.png and the strips\n";
    return cli::kExitOk;
}

void addBenchCommand(cli::ToolCli& tool) {
    auto a = std::make_shared<BenchArgs>();
    BenchOptions& o = a->o;
    CLI::App* sub = tool.addSubcommand(
        "bench", "measure every method's time and error against the ground truth",
        kBenchDescription, kOutputAndExitNote,
        [a](std::ostream& out) { return runBenchCommand(*a, out); });
    sub->add_option("--scene", o.scenes,
                    "a scene to bench (repeatable; default: room, truck_room, bowl_room and "
                    "sky_only)")
        ->allow_extra_args(false);
    sub->add_flag("--quick", o.quick,
                  "small frame (160x120), 64^2 probe faces, fewer frames and d_e values");
    sub->add_option("--out", o.outDir, "output folder")->check(cli::nonEmpty("a folder"));
    sub->add_option("--size", a->size, "frame size (default 1024x768, quick 160x120)")
        ->check(cli::sizeText());
    sub->add_option("--face-res", a->faceRes,
                    "cube face resolution of the baked probes (default 256, quick 64)")
        ->check(CLI::Range(8, 2048));
    sub->add_option("--max-frames", a->maxFrames,
                    "timed frames per row at most (default 64, quick 12)")
        ->check(CLI::Range(4, 1000));
    tool.allowEmpty(sub->add_option(
        "--sky", o.sky, "equirectangular panorama (default: the bundled field.jpg; '': black)"));
    sub->add_option("--pem-supersample", o.pemSupersample,
                    "rays per pixel side of the PEM bakes (default 1)")
        ->check(CLI::Range(1, 16));
    sub->add_option("--pem-rows", o.pemRows,
                    "the PEM rendering matrix's rows (specula-cook bake --rows): pixel, centre "
                    "or subray (default)")
        ->check(CLI::IsMember({"pixel", "centre", "subray"}));
    sub->add_option("--pem-non-negative", a->pemNonNegative,
                    "the PEM bakes keep their texels >= 0 by re-solving (specula-cook bake "
                    "--non-negative): on (default) or off")
        ->check(CLI::IsMember({"on", "off"}));
    sub->add_option("--pem-samples", o.pemSamples,
                    "the PEM sample counts to bake, e.g. 16 or 4,16 (default 4,8,16,32 on the "
                    "room and the bowl, 8 elsewhere and with --quick)")
        ->delimiter(',')
        ->check(CLI::Range(1, 1024));
    sub->add_option("--pem-path", o.pemPath,
                    "the PEM viewpoint's path: the scene camera's glTF animation (camera), the "
                    "walk's orbit (orbit), or auto (default): camera where the scene's camera "
                    "is animated, else orbit")
        ->check(CLI::IsMember({"auto", "orbit", "camera"}));
    sub->add_option("--pem-rounding-reach", o.pemRoundingReach,
                    "the PEM bakes' rows for the lookups the display's rounding reaches, in "
                    "metres and radians (specula-cook bake --rounding-reach; 0: off)")
        ->check(CLI::Range(0.0, 0.01));
    addReflectorOption(sub, a->addedReflectors, " (added to every benched scene)");
}

} // namespace

int runCli(std::span<const std::string> args, std::ostream& out, std::ostream& err) {
    cli::ToolCli tool("specula-sandbox",
                      "Walks reflectors through a scene and measures what accuracy costs in time.");
    addWalkCommand(tool);
    addLevelCommand(tool);
    addBenchCommand(tool);
    addGlossyCommand(tool);
    addHostCommand(tool);
    return tool.run(args, out, err);
}

} // namespace specula::sandbox
