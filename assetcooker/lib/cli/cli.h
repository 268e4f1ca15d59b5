#pragma once
// The specula-cook command line (CLI11, see tool_cli.h): one subcommand per command file.
// Adding a subcommand is one add*Command line in runCli (cli.cpp).
#include "assetcooker/lib/cli/tool_cli.h"

#include <ostream>
#include <span>
#include <string>

namespace specula::cook {

using cli::kExitCancelled;
using cli::kExitFailure;
using cli::kExitOk;
using cli::kExitUsage;

// Runs the tool on argv[1..]; returns the process exit code. Never throws.
int runCli(std::span<const std::string> args, std::ostream& out, std::ostream& err);

} // namespace specula::cook
