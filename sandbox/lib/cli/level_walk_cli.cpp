// specula-sandbox level: the command line of runLevelWalk (level_walk.h).
#include "assetcooker/lib/cli/tool_cli.h"
#include "engine/core/error.h"
#include "engine/core/regular_file.h"
#include "sandbox/lib/cli/added_reflector_flag.h"
#include "sandbox/lib/cli/created_output_folder.h"
#include "sandbox/lib/flavours/distance/level_walk.h"
#include "sandbox/lib/render/reflection_scene.h"

#include <memory>
#include <sstream>

namespace specula::sandbox {

namespace {

constexpr const char* kLevelDescription =
    "Walks the reflectors of SCENE through a level of distance probes (every \"specula_probe\"\n"
    "node: position, proxy, influence box or sphere, blend distance, priority; see\n"
    "`specula-cook bake --help`) while a camera follows them, and looks every reflector pixel\n"
    "up three ways on the CPU twin of the distance lookup: the nearest probe alone,\n"
    "engine-style blending (influence volumes, blend distances, priorities; up to K probes,\n"
    "the rest from the sky) and visibility-aware blending (a probe counts only where it sees\n"
    "the reflector point and the hit its search proposes, so a probe behind a wall adds\n"
    "nothing). Each is compared with Embree's environment-only ground truth on the reflector\n"
    "pixels.\n"
    "\n"
    "The level is baked into DIR/level first unless --level names a baked one; a baked one\n"
    "whose recorded geometry (or sky, when --sky is given) differs from SCENE's is refused\n"
    "(--allow-stale walks it with a warning per probe). The path runs\n"
    "through every probe in order (--path through, the default) unless --path gives points,\n"
    "inline or as @FILE.\n"
    "\n"
    "Writes DIR/frames.csv (per frame: reflector position, PSNR per blend, the engine's\n"
    "probes and weights at the reflector, the share of probe lookups hidden from their probe,\n"
    "pixels that fell back to the engine's blend), DIR/summary.csv (mean and worst PSNR on all\n"
    "frames and on the frames where two or more probes overlap; the pop metric: the largest\n"
    "frame-to-frame RMS change of the reflector pixels beside the truth's own change) and\n"
    "DIR/level_walk.png (truth and the three blends at the frame where engine-style blending\n"
    "is worst, error maps below).\n"
    "\n"
    "Unless --no-timing, the level is also drawn on the GPU (the level shader) for every blend\n"
    "and K = 1, 2, 4 at the frame where probes overlap with the most reflector pixels, and\n"
    "its reflector pass is timed against\n"
    "one probe's envmap pass: DIR/timing.csv (ms and ratio_to_envmap; on a software\n"
    "rasteriser only the ratios mean something).\n"
    "\n"
    "--roughness R gives every reflector that perceptual roughness (issue 14; a reflector\n"
    "with a roughness map reads R times the map's G at each pixel's TEXCOORD_0): the truth is\n"
    "Embree's GGX reflection (--samples a pixel), each probe's share is its own glossy sample\n"
    "(its GGX chain read at its own hit, the footprint level there) blended with the mirror's\n"
    "weights, times the GGX albedo; psnr_visibility_mirror_lookup (frames.csv, and the\n"
    "summary's \"visibility (mirror lookup)\" row) is the visibility blend's mirror lookup\n"
    "against the same truth, which is what a rough reflector drew before. The log gives the\n"
    "level's texture memory with and without the chains; the timed level passes draw the\n"
    "glossy shader, and timing.csv gains the mirror level's visibility K = 4 pass\n"
    "(\"visibility (mirror)\"), timed in the same rounds.\n";

struct LevelArgs {
    LevelWalkOptions o;
    std::string size = "320x240", path;
    std::vector<std::string> probes, addedReflectors;
    CLI::Option* sky = nullptr;
};

constexpr std::uint64_t kMaxPathFileBytes = 64 << 20;

// "x,y,z;x,y,z;..." ("through" or nothing: every probe in order), or "@FILE" with one
// x,y,z per line ('#' starts a comment line).
std::vector<glm::vec3> parsePath(const std::string& text) {
    std::vector<glm::vec3> points;
    if (text.empty() || text == "through") return points;
    const bool file = text.front() == '@';
    std::stringstream in;
    if (file) {
        // A regular file only: a FIFO would block the read forever, a folder read as no point.
        try {
            in << readRegularFile(text.substr(1), kMaxPathFileBytes);
        } catch (const Error& e) {
            throw UsageError("--path", "cannot read the path file: " + std::string(e.what()));
        }
    } else {
        in << text;
    }
    int line = 0;
    for (std::string point; std::getline(in, point, file ? '\n' : ';');) {
        ++line;
        point.erase(0, point.find_first_not_of(" \t\r"));
        point.erase(point.find_last_not_of(" \t\r") + 1);
        if (point.empty() || point.front() == '#') continue;
        if (!cli::vec3Text()(point).empty())
            throw UsageError("--path", (file ? text.substr(1) + " line " + std::to_string(line) +
                                                   ": expected x,y,z"
                                             : std::string("expected x,y,z;x,y,z;...")) +
                                           ", got '" + point + "'");
        points.push_back(cli::parseVec3(point));
    }
    return points;
}

} // namespace

void addLevelCommand(cli::ToolCli& tool) {
    auto a = std::make_shared<LevelArgs>();
    LevelWalkOptions& o = a->o;
    o.sky = defaultSkyPath();
    CLI::App* sub = tool.addSubcommand(
        "level", "walk a reflector through a level's probes and compare the ways to blend them",
        kLevelDescription,
        "exit status: 0 ok, 1 the input could not be processed, 2 bad command line\n",
        [a](std::ostream& out) {
            cli::parseSize(a->size, a->o.width, a->o.height);
            a->o.path = parsePath(a->path);
            for (const std::string& p : a->probes)
                a->o.probes.push_back(cli::parseVec3(p));
            a->o.addedReflectors = parseAddedReflectors(a->addedReflectors);
            a->o.skyFromLevel = !a->o.level.empty() && a->sky->count() == 0;
            CreatedOutputFolder created(a->o.out);
            runLevelWalk(a->o, out);
            created.keep();
            return cli::kExitOk;
        });
    sub->add_option("SCENE", o.scene, "the glTF/GLB scene")->required();
    sub->add_option("--out", o.out, "output folder")->required()->check(cli::nonEmpty("a folder"));
    sub->add_option("--level", o.level, "a level folder baked by specula-cook bake (level.json)");
    sub->add_option("--path", a->path,
                    "the reflector's path: x,y,z;x,y,z;... (world space), @FILE (one x,y,z a "
                    "line), or through (default: every probe in order)");
    sub->add_option("--frames", o.frames, "frames along the path (default 40)")
        ->check(CLI::Range(2, 100000));
    sub->add_option("--size", a->size, "frame size (default 320x240)")->check(cli::sizeText());
    sub->add_option("--face-res", o.faceRes, "cube face resolution when baking (default 128)")
        ->check(CLI::Range(8, 2048));
    sub->add_option("--k", o.k, "probes blended per pixel at most (default 4)")
        ->check(CLI::Range(1, 8));
    sub->add_option("--method", o.method, "each probe's lookup (default secant)")
        ->check(CLI::IsMember({"envmap", "boxproj", "bisection", "secant", "march"}));
    sub->add_option("--de", o.tolerance, "rectification tolerance d_e in metres (default 0.01)")
        ->check(cli::finiteRange(1e-5, 10.0));
    a->sky = tool.allowEmpty(sub->add_option(
        "--sky", o.sky,
        "equirectangular panorama (default: a --level's own sky, else the bundled field.jpg; "
        "'': black)"));
    sub->add_option("--probe", a->probes,
                    "baking: a probe at x,y,z (repeatable; the i-th moves the markup's i-th)")
        ->check(cli::vec3Text());
    sub->add_option("--probes", o.probeList,
                    "baking: a probe list (JSON, as specula-cook bake --probes takes)")
        ->check(CLI::ExistingFile);
    addReflectorOption(sub, a->addedReflectors);
    sub->add_flag("--allow-stale", o.allowStale,
                  "walk a --level whose recorded geometry or sky differs from SCENE's "
                  "(a warning per probe instead of an error)");
    sub->add_flag("!--no-timing", o.timing, "skip the GPU pass timing (timing.csv)");
    sub->add_option("--roughness", o.roughness,
                    "every reflector's perceptual roughness, 0 .. 1 (default 0: mirrors; times its "
                    "roughness map where it has one)")
        ->check(cli::finiteRange(0.0, 1.0));
    sub->add_option("--samples", o.glossySamples,
                    "GGX truth samples per pixel at roughness > 0 (default 256)")
        ->check(CLI::Range(1, 65536));
}

} // namespace specula::sandbox
