#include "bake_command.h"

#include "assetcooker/lib/cook.h"
#include "assetcooker/lib/level_bake.h"
#include "components/reflection_probe/probe_folder.h"
#include "engine/core/error.h"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>

namespace specula::cook {

namespace {

constexpr const char* kBakeDescription =
    "Bakes the reflection probe of SCENE (.gltf/.glb) into DIR: manifest.json plus one float\n"
    "EXR cube map per layer (N x 6N, faces +X -X +Y -Y +Z -Z top to bottom; RGB radiance, A\n"
    "distance from the probe centre). Rays are traced with Embree on all cores.\n"
    "\n"
    "Probe placement: --probe, else the first node whose extras hold \"specula_probe\": {...}\n"
    "(members: cell_size), else the centre of the reflectors. Reflectors are the nodes with\n"
    "\"specula_reflector\": true or {\"f0\": F}, and the meshes whose material has metallic\n"
    ">= 0.9 and roughness <= 0.1 (F0 its base colour's luminance) unless a node above says\n"
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
    "float EXR per sample. The bake measures its maps against the ray tracer at the samples\n"
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
    "with a [bake] section, e.g. face-res = 128; flags on the command line win.\n";

constexpr const char* kBakeFooter =
    "Signals: SIGINT/SIGTERM at any moment before the final rename leave DIR as it was and\n"
    "no temporary folder behind. DIR is replaced only if it is empty or a cooked probe that\n"
    "holds nothing but the files its manifest lists, and never if it holds SCENE. Temporary\n"
    "folders of killed bakes (DIR.tmp-PID of a process that no longer runs) are removed.\n"
    "\n"
    "exit status: 0 ok, 1 the scene could not be baked, 2 bad command line, 130 cancelled\n"
    "by SIGINT/SIGTERM (DIR left as it was)\n";

// What the bake's flags set; defaults are the help's.
struct BakeArgs {
    std::string scene, out, flavour = "distance";
    std::vector<std::string> probes; // --probe, repeatable
    std::optional<std::string> probeList, sky;
    // distance and pem
    std::optional<int> faceRes; // distance: 256, pem: 128
    // distance
    std::string layers = "plan", glossy = "auto";
    // lightfield
    std::optional<float> cellSize;
    std::optional<std::string> cellCentre;
    int cameras = 8, imageRes = 64;
    std::string compress = "none";
    // pem
    int samples = 8, supersample = 1;
    std::string imageSize = "640x480", geometry = "distance";
    float prior = 0.05f, smoothness = 0.02f;
    std::string parameter = "viewpoint", path = "orbit";
    // The options that belong to some flavours only, with their names ("distance|pem").
    std::vector<std::pair<const CLI::Option*, std::string>> flavourOnly;
};

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

// The cooking options the flags give (the flavour's settings by --flavour).
CookOptions cookOptions(const BakeArgs& a) {
    CookOptions o;
    o.scene = a.scene;
    o.out = a.out;
    if (a.sky) o.sky = *a.sky;
    if (a.probes.size() == 1) o.probeCentre = cli::parseVec3(a.probes.front());
    if (a.flavour == "lightfield") {
        LightFieldCookSettings s;
        if (a.cellCentre) s.cellCentre = cli::parseVec3(*a.cellCentre);
        s.cellSize = a.cellSize;
        s.cameras = a.cameras;
        s.imageRes = a.imageRes;
        s.compression =
            a.compress == "bc1" ? LightFieldCompression::BC1 : LightFieldCompression::None;
        o.flavour = s;
    } else if (a.flavour == "pem") {
        PemCookSettings s;
        s.samples = a.samples;
        s.faceRes = a.faceRes.value_or(s.faceRes);
        s.supersample = a.supersample;
        cli::parseSize(a.imageSize, s.imageWidth, s.imageHeight); // validated by the option
        s.parameter = a.parameter;
        s.path = a.path;
        s.geometry = a.geometry;
        s.priorWeight = a.prior;
        s.regularisation = a.smoothness;
        o.flavour = s;
    } else {
        DistanceCookSettings s;
        s.faceRes = a.faceRes.value_or(s.faceRes);
        s.planned = a.layers == "plan";
        s.glossy = a.glossy == "on"    ? GlossyBake::On
                   : a.glossy == "off" ? GlossyBake::Off
                                       : GlossyBake::Auto; // validated by the option
        o.flavour = s;
    }
    return o;
}

void printLightFieldSummary(const BakeArgs& a, const CookResult& r, double seconds,
                            std::ostream& out) {
    const auto& asset = std::get<LightFieldAsset>(r.asset);
    out << "baked light field: 6 slabs x " << a.cameras << "^2 cameras x " << a.imageRes
        << "^2 px, cell " << r.cellSize << " m, " << toString(asset.compression) << ", "
        << asset.diskBytes() << " bytes on disk, " << asset.gpuBytes()
        << " bytes of GPU memory, bake " << asset.bakeSeconds << " s, total " << seconds << " s -> "
        << a.out << "/manifest.json\n";
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

void printDistanceSummary(const BakeArgs& a, const CookResult& r, double seconds,
                          std::ostream& out) {
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
        out << "none (--glossy " << a.glossy
            << (a.glossy == "auto" ? ": every reflector is a mirror" : "") << ")\n";
    for (std::size_t i = 0; i < asset.layers.size(); ++i) {
        const DistanceProbeLayer& L = asset.layers[i];
        out << "  layer " << i << " " << L.name << ": d-bar " << L.avgDistance << " m, "
            << L.solidAngle << " sr, " << L.method << "\n";
    }
}

void printPemSummary(const BakeArgs& a, const CookResult& r, double seconds, std::ostream& out) {
    const auto& asset = std::get<PemAsset>(r.asset);
    const glm::vec3 box = asset.boxMax - asset.boxMin;
    out << "baked " << asset.samples.size() << " parameterized environment maps ("
        << asset.parameterKind << " along " << asset.path << ") at " << asset.faceRes
        << "^2 x 6, box " << box.x << " x " << box.y << " x " << box.z << " m, bake "
        << r.bakeSeconds << " s, total " << seconds << " s -> " << a.out << "/manifest.json\n";
    if (r.pemFits.empty()) return;
    // The cooker's own measurement against the ray tracer: what the maps are worth on the
    // baked viewpoints and half-way between them, where the runtime blends two.
    double on = 0, off = 0, worstOff = 1e9, infer = 0, worstInfer = 0, rays = 0;
    for (const PemSampleFit& f : r.pemFits) {
        on += f.psnrOn, off += f.psnrOff, infer += f.inferSeconds, rays += f.rays;
        worstOff = std::min(worstOff, f.psnrOff);
        worstInfer = std::max(worstInfer, f.inferSeconds);
    }
    const double n = double(r.pemFits.size());
    char line[256];
    std::snprintf(
        line, sizeof line,
        "fit against the ray tracer (%.0f reflector rays a sample, no Fresnel): on the samples "
        "%.1f dB, half-way between them %.1f dB (worst %.1f); inference %.2f s per sample "
        "(worst %.2f)\n",
        rays / n, on / n, off / n, worstOff, infer / n, worstInfer);
    out << line;
}

// A flag of other flavours is refused, not ignored.
void refuseOtherFlavoursOptions(const BakeArgs& a) {
    for (const auto& [option, flavours] : a.flavourOnly) {
        std::string names = flavours;
        std::replace(names.begin(), names.end(), '|', ' ');
        std::istringstream words(names);
        bool mine = false;
        for (std::string w; words >> w;)
            mine = mine || w == a.flavour;
        if (option->count() > 0 && !mine)
            throw UsageError(option->get_name(), "applies to --flavour " + flavours +
                                                     " only, not to --flavour " + a.flavour);
    }
}

// The flavour's settings as text: a change re-bakes a level's probes (the options checksum).
std::string optionsText(const BakeArgs& a) {
    std::ostringstream t;
    t << a.flavour << " face_res " << (a.faceRes ? *a.faceRes : 0) << " layers " << a.layers
      << " cell_size " << (a.cellSize ? *a.cellSize : 0.f) << " cameras " << a.cameras
      << " image_res " << a.imageRes << " compress " << a.compress << " glossy " << a.glossy;
    return t.str();
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

// A level: the scene has several probes, or the command line gives several (--probe twice,
// --probes FILE).
bool isLevel(const BakeArgs& a, const ProbeScene& scene) {
    return a.probeList || a.probes.size() > 1 || scene.markup.probes.size() > 1;
}

int runBake(const BakeArgs& a, std::ostream& out) {
    refuseOtherFlavoursOptions(a);
    const bool lightField = a.flavour == "lightfield";
    if (lightField && a.cameras * a.imageRes > 16384)
        throw UsageError("--cameras",
                         "NUM x --image-res RES = " + std::to_string(a.cameras * a.imageRes) +
                             " exceeds 16384 (the 2D texture side)");
    const CookOptions options = cookOptions(a);
    // A PEM setting the flags got wrong (say --path line with the viewpoint parameter) is a
    // usage error naming the flag, found before the scene is opened.
    if (const auto* pem = std::get_if<PemCookSettings>(&options.flavour)) {
        try {
            validatePemCookSettings(*pem, a.scene);
        } catch (const Error& e) {
            throw UsageError(e.field(), e.message()); // the tool names the field's flag
        }
    }
    const SignalGuard guard; // first: a signal during the load and the plan is honoured too
    const auto start = std::chrono::steady_clock::now();
    ProbeScene scene(options.scene, options.sky);
    throwIfCancelled(options.out);
    if (isLevel(a, scene)) {
        if (a.flavour == "pem")
            throw UsageError("--flavour", "pem bakes one probe's camera path, not a level of " +
                                              std::to_string(std::max<std::size_t>(
                                                  a.probes.size(), scene.markup.probes.size())) +
                                              " probes: give one --probe");
        LevelCookOptions level;
        level.cook = options;
        level.cook.probeCentre.reset();
        level.optionsText = optionsText(a);
        for (const std::string& p : a.probes)
            level.sources.positions.push_back(cli::parseVec3(p));
        if (a.probeList) level.sources.file = *a.probeList;
        printLevelSummary(cookLevel(scene, level, &out), out);
        return cli::kExitOk;
    }
    const CookResult r = cookProbe(scene, options, &out);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (lightField)
        printLightFieldSummary(a, r, seconds, out);
    else if (a.flavour == "pem")
        printPemSummary(a, r, seconds, out);
    else
        printDistanceSummary(a, r, seconds, out);
    return cli::kExitOk;
}

// BC1 blocks (4x4 texels) must not straddle two cameras of an atlas.
CLI::Validator multipleOfFour() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            int v = 0;
            return CLI::detail::lexical_cast(text, v) && v % 4 == 0
                       ? std::string()
                       : "expected a multiple of 4 (BC1 blocks), got '" + text + "'";
        },
        "");
}

} // namespace

void addBakeCommand(cli::ToolCli& tool) {
    auto a = std::make_shared<BakeArgs>();
    CLI::App* sub = tool.addSubcommand(
        "bake", "bake a scene's reflection probe into a cooked folder", kBakeDescription,
        kBakeFooter, [a](std::ostream& out) { return runBake(*a, out); });
    sub->add_option("SCENE", a->scene, "the glTF/GLB scene")->required();
    sub->add_option("--out", a->out, "output folder (replaced atomically; never half-written)")
        ->required()
        ->check(cli::nonEmpty("a folder"));
    sub->add_option("--flavour", a->flavour, "probe flavour")
        ->check(CLI::IsMember({"distance", "lightfield", "pem"}));
    sub->add_option("--probe", a->probes,
                    "probe centre in world space (overrides the markup's); repeat it for a "
                    "level of several probes")
        ->check(cli::vec3Text());
    sub->add_option("--probes", a->probeList,
                    "a probe list (JSON: {\"probes\": [{\"name\", \"position\", \"proxy\", "
                    "\"influence\", \"blend_distance\", \"priority\", \"cell_size\"}]}): "
                    "bakes a level")
        ->check(CLI::ExistingFile);
    sub->add_option("--sky", a->sky,
                    "equirectangular panorama for the distant environment (default: black)");

    auto only = [&](CLI::Option* o, const char* flavour) {
        std::string group = flavour;
        std::replace(group.begin(), group.end(), '|', '/');
        o->group(group + " options");
        a->flavourOnly.emplace_back(o, flavour);
        return o;
    };
    only(sub->add_option("--face-res", a->faceRes,
                         "cube face resolution (distance: default 256; pem: default 128, at most "
                         "1024)"),
         "distance|pem")
        ->check(CLI::Range(1, 4096));
    only(sub->add_option("--layers", a->layers,
                         "plan: the layers and methods of the effect plan (specula-cook plan); "
                         "objects: one layer per object"),
         "distance")
        ->check(CLI::IsMember({"plan", "objects"}));
    only(sub->add_option("--glossy", a->glossy,
                         "the composite's GGX prefiltered chain for glossy reflectors (5 levels, "
                         "roughness 0.2 .. 1, layer_00_ggx_<i>.exr): auto (default) when a "
                         "reflector has roughness > 0, on, off"),
         "distance")
        ->check(CLI::IsMember({"auto", "on", "off"}));
    only(sub->add_option("--cell-size", a->cellSize,
                         "cell side in metres (default: the probe's cell_size, else 1.5)"),
         "lightfield")
        ->check(cli::finiteRange(1e-3, 1e4));
    only(sub->add_option("--cell-center", a->cellCentre,
                         "cell centre in world space (default: the probe position)"),
         "lightfield")
        ->check(cli::vec3Text());
    only(sub->add_option("--cameras", a->cameras, "cameras per side of a slab"), "lightfield")
        ->check(CLI::Range(2, 256));
    only(sub->add_option("--image-res", a->imageRes, "pixels per side of a camera image"),
         "lightfield")
        ->check(CLI::Range(4, 4096))
        ->check(multipleOfFour());
    only(sub->add_option("--compress", a->compress,
                         "none: sRGB RGB8; bc1: DXT1 (bc7 is not supported: no BC7 encoder)"),
         "lightfield")
        ->check(CLI::IsMember({"none", "bc1"}));
    only(sub->add_option("--samples", a->samples,
                         "parameter samples: one inferred map per viewpoint t = k/N (default 8)"),
         "pem")
        ->check(CLI::Range(1, kMaxPemSamples));
    only(sub->add_option("--image-size", a->imageSize,
                         "the camera image the maps are inferred for: bake at the frame size "
                         "they will be drawn at (default 640x480, the walk's)"),
         "pem")
        ->check(cli::sizeText());
    only(sub->add_option("--supersample", a->supersample,
                         "S x S rays per reflector pixel (default 1: the pixel centres the "
                         "rasteriser shades)"),
         "pem")
        ->check(CLI::Range(1, 16));
    only(sub->add_option("--geometry", a->geometry,
                         "the maps' geometry: distance (rectified against the environment's "
                         "distance cube, traced at the face resolution; default) or box (the "
                         "environment's bounding box)"),
         "pem")
        ->check(CLI::IsMember({"box", "distance"}));
    only(sub->add_option("--prior", a->prior,
                         "distance geometry: weight pulling texels towards the radiance captured "
                         "at the centre, where the camera sees nothing (default 0.05; 0: none)"),
         "pem")
        ->check(cli::finiteRange(0.0, 100.0));
    only(sub->add_option("--smoothness", a->smoothness,
                         "weight of the rows tying every texel to its neighbours (default 0.02)"),
         "pem")
        ->check(cli::finiteRange(0.0, 100.0));
    only(sub->add_option("--parameter", a->parameter,
                         "what the maps vary with: viewpoint (the camera moves, default) or "
                         "reflector (the reflectors move before the scene camera)"),
         "pem")
        ->check(CLI::IsMember({"viewpoint", "reflector"}));
    only(sub->add_option("--path", a->path,
                         "the path the parameter runs along: orbit (the walk's camera orbit, or "
                         "the reflectors' orbit), line or figure8 (reflector only); camera (a "
                         "glTF camera animation) is refused: not read yet"),
         "pem");

    // Library code names the fields it read; these are the flags that set them.
    tool.mapField("face_res", "--face-res");
    tool.mapField("centre", "--probe");
    tool.mapField("cell_centre", "--cell-center");
    tool.mapField("cell.size", "--cell-size");
    tool.mapField("cameras", "--cameras");
    tool.mapField("image_res", "--image-res");
    tool.mapField("samples", "--samples");
    tool.mapField("supersample", "--supersample");
    tool.mapField("image_size", "--image-size");
    tool.mapField("parameter", "--parameter");
    tool.mapField("path", "--path");
    tool.mapField("geometry", "--geometry");
    tool.mapField("prior_weight", "--prior");
    tool.mapField("regularisation", "--smoothness");
}

} // namespace specula::cook
