#pragma once
// `specula-cook shards`, `bake-shard` and `merge`: a level's bake as shards (shard_bake.h).
#include "assetcooker/lib/cli/tool_cli.h"

namespace specula::cook {

void addShardCommands(cli::ToolCli& tool);

} // namespace specula::cook
