#include "assetcooker/lib/cli/bake_args.h"

#include "engine/core/error.h"

#include <algorithm>
#include <sstream>

namespace specula::cook {

namespace {

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
        s.localLayer = a.localLayer;
        s.mipLevels = a.mipLevels;
        s.rows = a.rows;
        s.nonNegative = a.nonNegative == "on";
        s.roundingReach = a.roundingReach;
        s.compression = a.compress;
        o.flavour = s;
    } else {
        DistanceCookSettings s;
        s.faceRes = a.faceRes.value_or(s.faceRes);
        s.planned = a.layers == "plan";
        s.measuredPlan = a.plan == "measured";
        if (a.maxError) {
            try {
                s.maxError = parseErrorBudget(*a.maxError, "", "--max-error");
            } catch (const Error& e) {
                throw UsageError("--max-error", e.message());
            }
        }
        s.maxMibPerProbe = a.maxMibPerProbe;
        s.compression =
            a.compress == "bc6h" ? DistanceCompression::Bc6h : DistanceCompression::None;
        s.glossy = a.glossy == "on"    ? GlossyBake::On
                   : a.glossy == "off" ? GlossyBake::Off
                                       : GlossyBake::Auto; // validated by the option
        o.flavour = s;
    }
    return o;
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

CookOptions checkedCookOptions(const BakeArgs& a) {
    refuseOtherFlavoursOptions(a);
    if (a.compress == "bc6h" && a.flavour == "lightfield")
        throw UsageError("--compress", "bc6h applies to --flavour distance or pem (a light "
                                       "field compresses with bc1), not to --flavour " +
                                           a.flavour);
    if (a.compress == "bc1" && a.flavour != "lightfield")
        throw UsageError("--compress", "bc1 applies to --flavour lightfield (distance and PEM "
                                       "probes compress with bc6h), not to --flavour " +
                                           a.flavour);
    if (a.flavour == "lightfield" && a.cameras * a.imageRes > 16384)
        throw UsageError("--cameras",
                         "NUM x --image-res RES = " + std::to_string(a.cameras * a.imageRes) +
                             " exceeds 16384 (the 2D texture side)");
    CookOptions options = cookOptions(a);
    // A PEM setting the flags got wrong (say --path line with the viewpoint parameter) is a
    // usage error naming the flag, found before the scene is opened.
    if (const auto* pem = std::get_if<PemCookSettings>(&options.flavour)) {
        try {
            validatePemCookSettings(*pem, a.scene);
        } catch (const Error& e) {
            throw UsageError(e.field(), e.message()); // the tool names the field's flag
        }
    }
    return options;
}

int checkedShardRows(const BakeArgs& a) {
    if (!a.shardRows) return 0;
    if (a.flavour != "lightfield")
        throw UsageError("--shard-rows",
                         "applies to --flavour lightfield (a " + a.flavour +
                             " probe is one shard: its bake is a GPU raster, not rays)");
    if (*a.shardRows < 1 || *a.shardRows > a.cameras)
        throw UsageError("--shard-rows", "expected 1 .. NUM = --cameras " +
                                             std::to_string(a.cameras) + ", got " +
                                             std::to_string(*a.shardRows));
    return *a.shardRows;
}

CLI::Option* addShardRowsOption(CLI::App* sub, std::optional<int>& rows) {
    return sub->add_option(
        "--shard-rows", rows,
        "light field: split each probe into part shards of N camera rows of one slab\n"
        "(6 x ceil(NUM / N) parts a probe, then the probe's assembly); 1 .. NUM, default NUM\n"
        "(one part a slab). The probe's bytes do not depend on it");
}

bool isLevel(const BakeArgs& a, const ProbeScene& scene) {
    return a.probeList || a.probes.size() > 1 || scene.markup.probes.size() > 1;
}

LevelCookOptions levelCookOptions(const BakeArgs& a, const CookOptions& options,
                                  const ProbeScene& scene) {
    if (a.flavour == "pem")
        throw UsageError("--flavour", "pem bakes one probe's camera path, not a level of " +
                                          std::to_string(std::max<std::size_t>(
                                              a.probes.size(), scene.markup.probes.size())) +
                                          " probes: give one --probe");
    LevelCookOptions level;
    level.cook = options;
    level.cook.probeCentre.reset();
    for (const std::string& p : a.probes)
        level.sources.positions.push_back(cli::parseVec3(p));
    if (a.probeList) level.sources.file = *a.probeList;
    return level;
}

LevelCookOptions shardedCookOptions(const BakeArgs& a, const CookOptions& options,
                                    const ProbeScene& scene, const char* flag) {
    if (a.flavour == "pem" && !isLevel(a, scene)) {
        LevelCookOptions pem;
        pem.cook = options;
        return pem;
    }
    if (!isLevel(a, scene))
        throw UsageError(flag, a.scene + " has one probe: `specula-cook bake` bakes it (shards "
                                         "split a level: several probes, --probe twice or "
                                         "--probes FILE; or a PEM's samples: --flavour pem)");
    return levelCookOptions(a, options, scene);
}

void addBakeOptions(cli::ToolCli& tool, CLI::App* sub, BakeArgs& a) {
    sub->add_option("SCENE", a.scene, "the glTF/GLB scene")->required();
    sub->add_option("--out", a.out, "output folder (replaced atomically; never half-written)")
        ->required()
        ->check(cli::nonEmpty("a folder"));
    sub->add_option("--flavour", a.flavour, "probe flavour")
        ->check(CLI::IsMember({"distance", "lightfield", "pem"}));
    sub->add_option("--probe", a.probes,
                    "probe centre in world space (overrides the markup's); repeat it for a "
                    "level of several probes")
        ->check(cli::vec3Text());
    sub->add_option("--probes", a.probeList,
                    "a probe list (JSON: {\"probes\": [{\"name\", \"position\", \"proxy\", "
                    "\"influence\", \"blend_distance\", \"priority\", \"cell_size\"}]}): "
                    "bakes a level")
        ->check(CLI::ExistingFile);
    tool.allowEmpty(
        sub->add_option("--sky", a.sky,
                        "equirectangular panorama for the distant environment (default and '': "
                        "black)"));

    auto only = [&](CLI::Option* o, const char* flavour) {
        std::string group = flavour;
        std::replace(group.begin(), group.end(), '|', '/');
        o->group(group + " options");
        a.flavourOnly.emplace_back(o, flavour);
        return o;
    };
    only(sub->add_option("--face-res", a.faceRes,
                         "cube face resolution (distance: default 256; pem: default 128, at most "
                         "1024)"),
         "distance|pem")
        ->check(CLI::Range(1, 4096));
    only(sub->add_option("--layers", a.layers,
                         "plan: the layers and methods of the effect plan (specula-cook plan); "
                         "objects: one layer per object"),
         "distance")
        ->check(CLI::IsMember({"plan", "objects"}));
    only(sub->add_option("--plan", a.plan,
                         "with --layers plan: measured (default: candidates scored against "
                         "Embree, the cheapest meeting --max-error; it may bake at half "
                         "--face-res) or analytic (thresholds)"),
         "distance")
        ->check(CLI::IsMember({"measured", "analytic"}));
    only(sub->add_option("--max-error", a.maxError,
                         "measured plan's budget over reflector rays: a PSNR (\"32dB\") or an "
                         "RMSE (\"rmse:0.03\"); default: the probe node's max_error"),
         "distance");
    only(sub->add_option(
             "--max-mib-per-probe", a.maxMibPerProbe,
             "measured plan: the most MiB a probe's textures may take on the GPU (cube "
             "maps and sky); "
             "every candidate is also weighed with its composite in BC6H (--compress bc6h), so "
             "the plan picks face size and format; candidates over it are left out, "
             "and the smallest is used when none fits"),
         "distance")
        ->check(cli::finiteRange(0.01, 1e6));
    only(sub->add_option("--glossy", a.glossy,
                         "the composite's GGX prefiltered chain for glossy reflectors (5 levels, "
                         "roughness 0.2 .. 1, layer_00_ggx_<i>.ktx2): auto (default) when a "
                         "reflector has roughness > 0, on, off"),
         "distance")
        ->check(CLI::IsMember({"auto", "on", "off"}));
    only(sub->add_option("--cell-size", a.cellSize,
                         "cell side in metres (default: the probe's cell_size, else 1.5)"),
         "lightfield")
        ->check(cli::finiteRange(1e-3, 1e4));
    only(sub->add_option("--cell-center", a.cellCentre,
                         "cell centre in world space (default: the probe position)"),
         "lightfield")
        ->check(cli::vec3Text());
    only(sub->add_option("--cameras", a.cameras, "cameras per side of a slab"), "lightfield")
        ->check(CLI::Range(2, 256));
    only(sub->add_option("--image-res", a.imageRes, "pixels per side of a camera image"),
         "lightfield")
        ->check(CLI::Range(4, 4096))
        ->check(multipleOfFour());
    only(sub->add_option("--compress", a.compress,
                         "distance: none (default: RGBA float cubes) or bc6h (the composite's "
                         "radiance in BC6H, its distance R16F where halves hold it within the "
                         "lookup's d_e, else R32F: asset format 3.0); light field: none (sRGB "
                         "RGB8) or bc1 (DXT1; bc7 is not supported: no BC7 encoder); pem: none "
                         "(float RGB maps) or bc6h (every sample map and MIP level in BC6H: "
                         "asset format 3.2)"),
         "distance|lightfield|pem")
        ->check(CLI::IsMember({"none", "bc1", "bc6h"}));
    only(sub->add_option("--samples", a.samples,
                         "parameter samples: one inferred map per viewpoint t = k/N (default 8)"),
         "pem")
        ->check(CLI::Range(1, kMaxPemSamples));
    only(sub->add_option("--image-size", a.imageSize,
                         "the camera image the maps are inferred for: bake at the frame size "
                         "they will be drawn at (default 640x480, the walk's)"),
         "pem")
        ->check(cli::sizeText());
    only(sub->add_option("--supersample", a.supersample,
                         "S x S rays per reflector pixel (default 1: the pixel centres the "
                         "rasteriser shades)"),
         "pem")
        ->check(CLI::Range(1, 16));
    only(sub->add_option("--geometry", a.geometry,
                         "the maps' geometry: distance (rectified against the environment's "
                         "distance cube, traced at the face resolution; default) or box (the "
                         "environment's bounding box)"),
         "pem")
        ->check(CLI::IsMember({"box", "distance"}));
    only(sub->add_option("--prior", a.prior,
                         "distance geometry: weight pulling texels towards the radiance captured "
                         "at the centre, where the camera sees nothing (default 0.05; 0: none)"),
         "pem")
        ->check(cli::finiteRange(0.0, 100.0));
    only(sub->add_option("--smoothness", a.smoothness,
                         "weight of the rows tying every texel to its neighbours (default 0.02)"),
         "pem")
        ->check(cli::finiteRange(0.0, 100.0));
    only(sub->add_option("--local-layer", a.localLayer,
                         "the local layer (what a concave reflector shows of itself, over the "
                         "distant map off the reflector's hull): auto (where reflector rays meet "
                         "their own reflector again, measured; default), on or off"),
         "pem")
        ->check(CLI::IsMember({"auto", "on", "off"}));
    only(sub->add_option("--mip-levels", a.mipLevels,
                         "MIP levels of the distant maps, every level inferred together (the "
                         "paper's MIP inference; the shader picks the level from the pixel's "
                         "footprint): 1 (default) .. log2(face res) + 1"),
         "pem")
        ->check(CLI::Range(1, 16));
    only(sub->add_option("--rows", a.rows,
                         "the rendering matrix's rows against the antialiased image (each "
                         "pixel's mean radiance over its --supersample sub-rays): pixel (the "
                         "mean of the sub-rays' lookups), centre (the lookup of the pixel's "
                         "centre ray, as the rasteriser draws it; odd --supersample), or subray "
                         "(one row per traced ray against its own radiance; default)"),
         "pem")
        ->check(CLI::IsMember({"pixel", "centre", "subray"}));
    only(sub->add_option("--non-negative", a.nonNegative,
                         "keep the inferred texels >= 0 (and the local layer's coverage in "
                         "[0, 1]) by re-solving with the crossing texels pinned at the bound, "
                         "instead of clamping afterwards: on (default) or off"),
         "pem")
        ->check(CLI::IsMember({"on", "off"}));
    only(sub->add_option("--rounding-reach", a.roundingReach,
                         "distance geometry: where moving a reflector ray's point or direction "
                         "by this much (metres; radians) along an axis makes the search end on "
                         "other texels, the moved ray becomes a row too, so the display, whose "
                         "interpolants differ from the tracer's by rounding, reads fitted texels "
                         "(default 1e-4; 0: off)"),
         "pem")
        ->check(CLI::Range(0.0, 0.01));
    only(sub->add_option("--parameter", a.parameter,
                         "what the maps vary with: viewpoint (the camera moves, default) or "
                         "reflector (the reflectors move before the scene camera)"),
         "pem")
        ->check(CLI::IsMember({"viewpoint", "reflector"}));
    only(sub->add_option("--path", a.path,
                         "the path the parameter runs along: orbit (the walk's camera orbit, or "
                         "the reflectors' orbit), line or figure8 (reflector only); camera "
                         "(viewpoint only: the scene camera's glTF animation, first key to last, "
                         "an open path whose two ends are samples)"),
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
    tool.mapField("local_layer", "--local-layer");
    tool.mapField("mip_levels", "--mip-levels");
    tool.mapField("rows", "--rows");
    tool.mapField("non_negative", "--non-negative");
    tool.mapField("rounding_reach", "--rounding-reach");
    tool.mapField("geometry", "--geometry");
    tool.mapField("prior_weight", "--prior");
    tool.mapField("regularisation", "--smoothness");
}

} // namespace specula::cook
