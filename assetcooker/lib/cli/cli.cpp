#include "assetcooker/lib/cli/cli.h"

#include "assetcooker/lib/cli/bake_command.h"
#include "assetcooker/lib/cli/plan_command.h"
#include "assetcooker/lib/cli/shard_commands.h"
#include "assetcooker/lib/inspect/inspect.h"
#include "assetcooker/lib/inspect/inspect_textures.h"

#include "engine/core/error.h"

#include <memory>

namespace specula::cook {

namespace {

void addInspectCommand(cli::ToolCli& tool) {
    auto file = std::make_shared<std::string>();
    auto exrDir = std::make_shared<std::string>();
    CLI::App* sub = tool.addSubcommand(
        "inspect", "print what a glTF/GLB file or cooked textures hold as one JSON object",
        "Loads FILE (.gltf or .glb, Draco-compressed meshes included) and prints one JSON\n"
        "object to stdout: meshes, primitives, vertices, triangles (each mesh counted once,\n"
        "however many nodes instance it), bounds {min, max} in world space, extensionsUsed,\n"
        "nodes, materials and warnings.\n"
        "\n"
        "Given a cooked probe or level folder, or one .ktx2 file, lists its KTX2 textures\n"
        "instead (file, format RGBA32F/RGBA16F/BC6H..., cube, width, height, levels, bytes);\n"
        "--dump-exr DIR also writes each as OpenEXR for a texture viewer (a cube as its\n"
        "N x 6N strip of faces +X -X +Y -Y +Z -Z, BC6H decoded; mip K as NAME_mipK.exr).\n",
        "exit status: 0 ok, 1 FILE could not be loaded, 2 bad command line\n",
        [file, exrDir](std::ostream& out) {
            if (isCookedTexturePath(*file)) {
                out << inspectTextures(*file, *exrDir).dump(2) << '\n';
                return kExitOk;
            }
            if (!exrDir->empty())
                throw UsageError("--dump-exr", "dumps cooked textures: give a probe or level "
                                               "folder or a .ktx2 file, not a scene");
            out << inspectScene(*file).dump(2) << '\n';
            return kExitOk;
        });
    sub->add_option("FILE", *file, "the glTF/GLB file, a cooked folder or a .ktx2 file")
        ->required();
    sub->add_option("--dump-exr", *exrDir,
                    "write the cooked textures as OpenEXR into DIR (debugging)");
}

} // namespace

int runCli(std::span<const std::string> args, std::ostream& out, std::ostream& err) {
    cli::ToolCli tool("specula-cook", "Bakes reflection probes from glTF scenes.");
    addInspectCommand(tool);
    addBakeCommand(tool);
    addPlanCommand(tool);
    addShardCommands(tool);
    return tool.run(args, out, err);
}

} // namespace specula::cook
