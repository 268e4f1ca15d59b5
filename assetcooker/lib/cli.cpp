#include "cli.h"

#include "assetcooker/lib/bake_command.h"
#include "assetcooker/lib/inspect.h"
#include "assetcooker/lib/plan_command.h"
#include "assetcooker/lib/shard_commands.h"

#include <memory>

namespace specula::cook {

namespace {

void addInspectCommand(cli::ToolCli& tool) {
    auto file = std::make_shared<std::string>();
    CLI::App* sub = tool.addSubcommand(
        "inspect", "print what a glTF/GLB file holds as one JSON object",
        "Loads FILE (.gltf or .glb, Draco-compressed meshes included) and prints one JSON\n"
        "object to stdout: meshes, primitives, vertices, triangles (each mesh counted once,\n"
        "however many nodes instance it), bounds {min, max} in world space, extensionsUsed,\n"
        "nodes, materials and warnings.\n",
        "exit status: 0 ok, 1 FILE could not be loaded, 2 bad command line\n",
        [file](std::ostream& out) {
            out << inspectScene(*file).dump(2) << '\n';
            return kExitOk;
        });
    sub->add_option("FILE", *file, "the glTF/GLB file")->required();
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
