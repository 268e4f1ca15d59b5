#pragma once
// `specula-cook plan`: prints the effect plan of a scene's probe without baking.
#include "assetcooker/lib/cli/tool_cli.h"

namespace specula::cook {

void addPlanCommand(cli::ToolCli& tool);

} // namespace specula::cook
