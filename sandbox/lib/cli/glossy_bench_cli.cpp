// specula-sandbox glossy: the command line of runGlossyBench (glossy_bench.h).
#include "assetcooker/lib/cli/tool_cli.h"
#include "sandbox/lib/bench/glossy_bench.h"
#include "sandbox/lib/cli/added_reflector_flag.h"
#include "sandbox/lib/cli/created_output_folder.h"
#include "sandbox/lib/render/reflection_scene.h"

#include <memory>

namespace specula::sandbox {

namespace {

constexpr const char* kGlossyDescription =
    "The glossy-reflection bench of issue 14, on the CPU twins of the lookups. A distance\n"
    "probe of SCENE (cooked with its GGX prefiltered chain; secant search, d_e 0.01 m) and a\n"
    "small light-field probe (8 x 8 cameras of 64^2 per slab) are baked once into DIR/probes.\n"
    "Then for each --roughness every reflector is given that perceptual roughness (alpha =\n"
    "roughness^2; its factor where it has a roughness map, see below), Embree traces the\n"
    "environment-only GGX ground truth (--samples samples a pixel, seed 1) and its noise\n"
    "floor (seed 1 against seed 2: a method's PSNR near it cannot be trusted), and every\n"
    "reflector pixel is looked up six ways:\n"
    "\n"
    "  envmap+chain                 the direction alone, chain level from roughness alone\n"
    "                               (what Filament does)\n"
    "  boxproj+chain                the box-projected direction, level from roughness alone\n"
    "                               (Unity, Godot)\n"
    "  rectified (roughness level)  the distance probe's mirror search for the hit, level\n"
    "                               from roughness alone (the comparison for the next)\n"
    "  rectified (footprint level)  the same hit, level from the lobe's footprint at the hit\n"
    "                               distance (ours; the shader's glossy distance lookup)\n"
    "  layered (footprint level)    every object layer searched (secant), the nearest hit's\n"
    "                               footprint level in the composite's chain\n"
    "  light field glossy           the light field's GGX filter (rays and mips)\n"
    "\n"
    "The five distance lookups give the normalised prefiltered lighting and are multiplied by\n"
    "the GGX directional albedo E(n.v, roughness), as the shaders do; the light field's lookup\n"
    "includes it. At roughness 0 every lookup is its mirror lookup.\n"
    "\n"
    "Roughness maps: --roughness is each reflector's roughness FACTOR. A reflector with a\n"
    "metallic-roughness texture (markup \"roughness\": \"material\", or a reflector found by\n"
    "its material) reads factor x the texture's G channel (linear) at each pixel's TEXCOORD_0,\n"
    "sampled bilinearly with repeat as the GPU does, in the truth, in every lookup and in the\n"
    "albedo. Where a reflector has one, a line per roughness also gives the rectified\n"
    "(footprint level) PSNR had each such reflector taken factor x its texture's mean\n"
    "roughness uniformly instead.\n"
    "\n"
    "Cost: unless --no-timing, the GPU reflector pass of every method with a shader\n"
    "(envmap+chain, boxproj+chain, rectified and layered (footprint level): the distance\n"
    "shader's glossy path with the envmap, boxproj, secant and layered methods; light field\n"
    "glossy: the light-field shader's) is timed per roughness from the scene's camera, in\n"
    "interleaved rounds, against the classic environment map's mirror pass of the same run:\n"
    "ratio_to_envmap (rectified (roughness level) has no shader: none). On a software\n"
    "rasteriser only the ratios mean anything. memory_mib: the textures the method holds (the\n"
    "composite cube and sky, the object layers' tiles for layered, at roughness > 0 the GGX\n"
    "chain, the albedo table and the reflectors' roughness maps; the light field's atlas, its\n"
    "mips, the table and the maps). The mirror methods' whole-frame figures come from\n"
    "`specula-sandbox bench`.\n"
    "\n"
    "Writes DIR/glossy.csv (roughness, method, psnr, noise_floor_psnr, ratio_to_envmap,\n"
    "memory_mib; PSNR in dB on the eroded reflector pixels) and prints the tables.\n";

struct GlossyArgs {
    GlossyBenchOptions o;
    std::string size = "320x240", roughness;
    std::vector<std::string> addedReflectors;
};

} // namespace

void addGlossyCommand(cli::ToolCli& tool) {
    auto a = std::make_shared<GlossyArgs>();
    GlossyBenchOptions& o = a->o;
    o.sky = defaultSkyPath();
    CLI::App* sub = tool.addSubcommand(
        "glossy", "compare the glossy lookups with the GGX ground truth, roughness by roughness",
        kGlossyDescription,
        "exit status: 0 ok, 1 the input could not be processed, 2 bad command line\n",
        [a](std::ostream& out) {
            cli::parseSize(a->size, a->o.width, a->o.height);
            if (!a->roughness.empty()) a->o.roughness = parseRoughnessList(a->roughness);
            a->o.addedReflectors = parseAddedReflectors(a->addedReflectors);
            CreatedOutputFolder created(a->o.out);
            runGlossyBench(a->o, out);
            created.keep();
            return cli::kExitOk;
        });
    sub->add_option("SCENE", o.scene, "the glTF/GLB scene")->required();
    sub->add_option("--out", o.out, "output folder")->required()->check(cli::nonEmpty("a folder"));
    sub->add_option("--roughness", a->roughness,
                    "perceptual roughness values in [0, 1], comma-separated: each reflector's "
                    "factor, times its roughness map where it has one (default "
                    "0,0.05,0.1,0.2,0.35,0.5)");
    sub->add_option("--size", a->size, "frame size (default 320x240)")->check(cli::sizeText());
    sub->add_option("--face-res", o.faceRes,
                    "cube face resolution of the distance probe "
                    "(default 128)")
        ->check(CLI::Range(8, 2048));
    sub->add_option("--samples", o.samples, "GGX truth samples per pixel (default 256)")
        ->check(CLI::Range(1, 65536));
    tool.allowEmpty(sub->add_option(
        "--sky", o.sky, "equirectangular panorama (default: the bundled field.jpg; '': black)"));
    sub->add_flag("!--no-timing", o.timing, "skip the GPU pass timing (ratio_to_envmap: none)");
    sub->add_option("--rounds", o.timingRounds,
                    "interleaved timing rounds: the median of as many frames per method "
                    "(default 15)")
        ->check(CLI::Range(1, 1000));
    addReflectorOption(sub, a->addedReflectors);
}

} // namespace specula::sandbox
