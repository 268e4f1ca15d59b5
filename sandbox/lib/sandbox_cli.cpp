#include "sandbox_cli.h"

#include "engine/core/error.h"
#include "engine/core/file_write.h"
#include "engine/core/flags.h"
#include "sandbox/lib/bench.h"
#include "sandbox/lib/bench_methods.h"
#include "sandbox/lib/walk.h"

#include <exception>
#include <filesystem>
#include <functional>
#include <regex>
#include <string_view>
#include <vector>

namespace specula::sandbox {

namespace {

constexpr int kExitOk = 0, kExitFailure = 1, kExitUsage = 2;

constexpr std::string_view kToolUsage = "usage: specula-sandbox <subcommand> [options] [args]\n"
                                        "       specula-sandbox <subcommand> --help\n";

// The end of every subcommand's --help.
constexpr std::string_view kOutputAndExitNote =
    "\n"
    "Every write is checked: a full disk or a short write fails the run (exit 1), and a\n"
    "failed run removes the --out folder again if it created it.\n"
    "\n"
    "exit status: 0 ok, 1 the input could not be processed, 2 bad command line\n";

constexpr std::string_view kWalkUsage =
    "usage: specula-sandbox walk MANIFEST_OR_SCENE [options]\n"
    "\n"
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
    "options:\n"
    "  --method M      envmap, boxproj, bisection (default), secant, avgdist, layered, plan\n"
    "                  (the cooked effect plan), lightfield (bakes a light field from a scene;\n"
    "                  a light-field manifest always draws with it)\n"
    "  --de D          rectification tolerance d_e in metres, 1e-5..10 (default 0.01)\n"
    "  --path P        orbit (default), line or figure8; within 0.2 cell sizes of the start\n"
    "  --frames N      headless: frames to write, 1..100000 (default 60); window: quit after\n"
    "                  N frames and play the path (default: run until closed)\n"
    "  --headless      no window: write frames to --out\n"
    "  --compare       headless: trace every frame's ground truth and add its PSNR\n"
    "  --out DIR       output folder (default walk-out)\n"
    "  --size WxH      frame size (default 640x480)\n"
    "  --scene FILE    the scene of a manifest (overrides its \"source\")\n"
    "  --sky FILE      equirectangular panorama (default: the bundled field.jpg)\n"
    "  --face-res N    cube face resolution when baking a scene, 8..2048 (default 128)\n"
    "  -h, --help      show this help\n";

constexpr std::string_view kBenchUsage =
    "usage: specula-sandbox bench [--scene S ...] [--quick] [--out DIR] [options]\n"
    "\n"
    "Sweeps every method and its accuracy parameters (d_e in {0.1, 0.03, 0.01, 0.003}; quick:\n"
    "{0.1, 0.01}) on each scene (default: the bundled room and truck_room), and measures per\n"
    "row: median reflector-pass time (GL timer queries on a GPU; wall clock around glFinish on\n"
    "CPU renderers such as llvmpipe, whose queries miss deferred rasterisation; as many frames\n"
    "as a stable median needs), its ratio to envmap in the same run, RMSE and PSNR against the "
    "Embree ground truth\n"
    "on reflector pixels (environment-only and full), texture fetches per pixel (CPU twin),\n"
    "probe GPU memory and bake time. The ground truth itself is a row.\n"
    "\n"
    "Writes DIR/bench.csv, DIR/bench.md (machine and renderer named), DIR/accuracy_vs_time.png\n"
    "(PSNR against time, one line per method, Pareto front ringed) and DIR/strip_<scene>.png\n"
    "(ground truth | envmap | boxproj | distance cubemap | light field, error maps below).\n"
    "\n"
    "options:\n"
    "  --scene FILE    a scene to bench (repeatable; default: room and truck_room)\n"
    "  --quick         small frame (160x120), 64^2 probe faces, fewer frames and d_e values\n"
    "  --out DIR       output folder (default bench-out)\n"
    "  --size WxH      frame size (default 1024x768, quick 160x120)\n"
    "  --face-res N    cube face resolution of the baked probes, 8..2048 (default 256, quick 64)\n"
    "  --max-frames N  timed frames per row at most, 4..1000 (default 64, quick 12)\n"
    "  --sky FILE      equirectangular panorama (default: the bundled field.jpg)\n"
    "  -h, --help      show this help\n";

// What walk and bench write into --out, partial outputs and temporaries included.
bool isOwnOutput(const std::string& name) {
    static const std::regex own(R"(((frame_\d+|contact_sheet|accuracy_vs_time|strip_.+)\.png)"
                                R"(|frames\.csv|bench\.(csv|md))(\.tmp-\d+)?)"
                                R"(|probes?(\.(tmp|old)-\d+)?)");
    return std::regex_match(name, own);
}

// A walk or bench that fails leaves no output folder it created: unless kept, the guard
// removes the folders --out made (create_directories may make several) on the way out,
// provided they hold nothing but this tool's own partial outputs.
class CreatedOutputFolder {
public:
    explicit CreatedOutputFolder(std::string dir)
        : dir_(std::move(dir)), created_(outermostMissingFolder(dir_)) {}
    CreatedOutputFolder(const CreatedOutputFolder&) = delete;
    CreatedOutputFolder& operator=(const CreatedOutputFolder&) = delete;
    void keep() { created_.clear(); }
    ~CreatedOutputFolder() {
        namespace fs = std::filesystem;
        if (created_.empty()) return;
        try {
            const std::vector<fs::directory_entry> entries(fs::directory_iterator(dir_),
                                                           fs::directory_iterator{});
            for (const fs::directory_entry& e : entries)
                if (!isOwnOutput(e.path().filename().string())) return;
            for (const fs::directory_entry& e : entries)
                fs::remove_all(e.path());
            removeEmptyFoldersUpTo(dir_, created_);
        } catch (const std::exception&) {
            // Leaving a folder behind is the lesser harm; the run's own error is reported.
        }
    }

private:
    std::string dir_;
    std::filesystem::path created_;
};

int runWalk(std::span<const std::string> args, std::ostream& out) {
    Flags flags(args);
    WalkOptions o;
    if (auto m = flags.value("--method"); m && !parseSandboxMethod(*m, o.method))
        throw UsageError{
            "--method: expected envmap, boxproj, bisection, secant, avgdist, layered, plan or "
            "lightfield, got '" +
            *m + "'"};
    o.tolerance = flags.floatValue("--de", 0.01f, 1e-5f, 10.f);
    if (auto p = flags.value("--path"); p && !parseWalkPath(*p, o.path))
        throw UsageError{"--path: expected orbit, line or figure8, got '" + *p + "'"};
    o.headless = flags.flag("--headless");
    o.frames = flags.intValue("--frames", o.headless ? 60 : 0, o.headless ? 1 : 0, 100000);
    o.compare = flags.flag("--compare");
    o.outDir = flags.value("--out").value_or(o.outDir);
    if (auto s = flags.value("--size")) parseSize("--size", *s, o.width, o.height);
    o.scene = flags.value("--scene");
    o.sky = flags.value("--sky");
    o.faceRes = flags.intValue("--face-res", o.faceRes, 8, 2048);
    const auto pos = flags.positionals();
    if (pos.size() != 1) throw UsageError{"walk needs exactly one MANIFEST_OR_SCENE"};
    if (o.outDir.empty()) throw UsageError{"--out: expected a folder"};
    if (o.compare && !o.headless) throw UsageError{"--compare needs --headless"};
    o.input = pos[0];
    CreatedOutputFolder created(o.outDir);
    const int status = o.headless ? runWalkHeadless(o, out) : runWalkWindow(o, out);
    if (status == kExitOk) created.keep();
    return status;
}

int runBenchCommand(std::span<const std::string> args, std::ostream& out) {
    Flags flags(args);
    BenchOptions o;
    o.scenes = flags.values("--scene");
    o.quick = flags.flag("--quick");
    o.outDir = flags.value("--out").value_or(o.outDir);
    if (auto s = flags.value("--size")) parseSize("--size", *s, o.width, o.height);
    o.faceRes = flags.intValue("--face-res", 0, 8, 2048);
    o.maxFrames = flags.intValue("--max-frames", 0, 4, 1000);
    o.sky = flags.value("--sky").value_or("");
    const auto pos = flags.positionals();
    if (!pos.empty())
        throw UsageError{"bench takes no positional argument (use --scene), got '" + pos[0] + "'"};
    if (o.outDir.empty()) throw UsageError{"--out: expected a folder"};
    CreatedOutputFolder created(o.outDir);
    const BenchReport r = runBench(o, out);
    created.keep();
    out << "wrote " << r.rows.size() << " rows to " << o.outDir << "/bench.csv, bench.md, "
        << "accuracy_vs_time.png and the strips\n";
    return kExitOk;
}

struct Subcommand {
    std::string_view name, summary, usage;
    std::function<int(std::span<const std::string>, std::ostream&)> run;
};

const std::vector<Subcommand>& subcommands() {
    static const std::vector<Subcommand> table = {
        {"walk", "walk the reflectors through a scene (window, or frames to disk)", kWalkUsage,
         runWalk},
        {"bench", "measure every method's time and error against the ground truth", kBenchUsage,
         runBenchCommand},
    };
    return table;
}

bool isHelp(const std::string& a) {
    return a == "--help" || a == "-h";
}

std::string firstLine(const std::string& s) {
    const auto n = s.find('\n');
    return n == std::string::npos ? s : s.substr(0, n);
}

} // namespace

int runCli(std::span<const std::string> args, std::ostream& out, std::ostream& err) {
    if (args.empty()) {
        err << kToolUsage << "specula-sandbox: error: missing subcommand (try --help)\n";
        return kExitUsage;
    }
    if (isHelp(args[0])) {
        out << kToolUsage
            << "\nWalks reflectors through a scene and measures what accuracy costs in time.\n"
            << "\nsubcommands:\n";
        for (const Subcommand& s : subcommands())
            out << "  " << s.name << std::string(10 - s.name.size(), ' ') << s.summary << '\n';
        out << "\noptions:\n  -h, --help  show this help\n";
        return kExitOk;
    }
    const Subcommand* sub = nullptr;
    for (const Subcommand& s : subcommands())
        if (s.name == args[0]) sub = &s;
    if (!sub) {
        err << kToolUsage << "specula-sandbox: error: "
            << (args[0].starts_with("-") ? "unknown option '" : "unknown subcommand '") << args[0]
            << "' (try --help)\n";
        return kExitUsage;
    }
    const auto rest = args.subspan(1);
    for (const std::string& a : rest) {
        if (a == "--") break;
        if (isHelp(a)) {
            out << sub->usage << kOutputAndExitNote;
            return kExitOk;
        }
    }
    try {
        return sub->run(rest, out);
    } catch (const UsageError& e) {
        err << "usage: specula-sandbox " << sub->name << " --help\n"
            << "specula-sandbox " << sub->name << ": error: " << e.message << '\n';
        return kExitUsage;
    } catch (const std::exception& e) {
        err << "specula-sandbox " << sub->name << ": error: " << firstLine(e.what()) << '\n';
    }
    return kExitFailure;
}

} // namespace specula::sandbox
