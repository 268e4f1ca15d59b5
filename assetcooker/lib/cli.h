#pragma once
// The specula-cook command line: a table of subcommands, each with its own help and
// argument parser. Adding a subcommand is one entry in subcommands() (cli.cpp).
#include "engine/core/flags.h"

#include <functional>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace specula::cook {

// Exit codes shared by every subcommand.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;     // the input could not be processed
inline constexpr int kExitUsage = 2;       // the command line itself is wrong
inline constexpr int kExitCancelled = 130; // 128 + SIGINT: stopped by a signal, nothing replaced

// Thrown by argument parsing; runCli prints it with the usage line and exits kExitUsage.
using UsageError = specula::UsageError;

struct Subcommand {
    std::string_view name;
    std::string_view summary; // one line, for the tool's --help
    std::string_view usage;   // full help text of the subcommand
    // Receives the arguments after the subcommand name; --help is handled before.
    std::function<int(std::span<const std::string> args, std::ostream& out, std::ostream& err)> run;
};

const std::vector<Subcommand>& subcommands();

// Runs the tool on argv[1..]; returns the process exit code. Never throws.
int runCli(std::span<const std::string> args, std::ostream& out, std::ostream& err);

} // namespace specula::cook
