// specula-sandbox host: the command line of runHostTiming (host_timing.h).
#include "assetcooker/lib/cli/tool_cli.h"
#include "sandbox/lib/cli/created_output_folder.h"
#include "sandbox/lib/flavours/distance/host_timing.h"
#include "sandbox/lib/render/reflection_scene.h"

#include <memory>

namespace specula::sandbox {

namespace {

constexpr const char* kHostDescription =
    "Draws one cooked distance probe on SCENE's reflectors two ways, in interleaved rounds:\n"
    "through Specula's own reflector pass (the sandbox) and through the host API as a host\n"
    "engine draws it (its own program over the same meshes: the shader text of\n"
    "DistanceHostProbe::glslLibrary() and its own main calling speculaReflect, bindTo before\n"
    "every draw, its own Schlick Fresnel). Both reflector passes are timed with one clock (GL\n"
    "timer queries on a GPU, the wall clock around glFinish on a software rasteriser, where\n"
    "only the ratio means something).\n"
    "\n"
    "Writes DIR/host.csv (per path: frames, the quartiles of the pass time in ms, the ratio\n"
    "of medians to the sandbox's, the host frame's PSNR against the sandbox's) and\n"
    "DIR/host.png (the sandbox's frame, the host's, their difference x 10). The probe is\n"
    "baked into DIR/probe unless --probe names a cooked one.\n";

} // namespace

void addHostCommand(cli::ToolCli& tool) {
    auto o = std::make_shared<HostTimingOptions>();
    o->sky = defaultSkyPath();
    auto size = std::make_shared<std::string>();
    CLI::App* sub = tool.addSubcommand(
        "host", "time the host API's path against the sandbox's on one view", kHostDescription,
        "exit status: 0 ok, 1 the input could not be processed, 2 bad command line\n",
        [o, size](std::ostream& out) {
            if (!size->empty()) cli::parseSize(*size, o->width, o->height);
            CreatedOutputFolder created(o->out);
            runHostTiming(*o, out);
            created.keep();
            return cli::kExitOk;
        });
    sub->add_option("SCENE", o->scene, "the glTF/GLB scene")->required();
    sub->add_option("--out", o->out, "output folder")->required()->check(cli::nonEmpty("a folder"));
    sub->add_option("--probe", o->probe, "a cooked distance probe's manifest.json (default: bake)");
    sub->add_option("--size", *size, "frame size (default 1024x768)")->check(cli::sizeText());
    sub->add_option("--face-res", o->faceRes, "cube face resolution of the bake (default 256)")
        ->check(CLI::Range(8, 2048));
    sub->add_option("--rounds", o->rounds, "interleaved timing rounds (default 31)")
        ->check(CLI::Range(1, 1000));
    tool.allowEmpty(sub->add_option(
        "--sky", o->sky, "equirectangular panorama (default: the bundled field.jpg; '': black)"));
}

} // namespace specula::sandbox
