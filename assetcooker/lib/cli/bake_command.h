#pragma once
// `specula-cook bake`: glTF scene in, cooked probe folder out.
#include "assetcooker/lib/cli/tool_cli.h"

namespace specula::cook {

void addBakeCommand(cli::ToolCli& tool);

} // namespace specula::cook
