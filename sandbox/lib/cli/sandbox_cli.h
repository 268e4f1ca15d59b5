#pragma once
// The specula-sandbox command line: walk and bench, each with its own help. Exit status 0
// ok, 1 the input could not be processed (one line naming the file), 2 bad command line.
#include <ostream>
#include <span>
#include <string>

namespace specula::sandbox {

int runCli(std::span<const std::string> args, std::ostream& out, std::ostream& err);

} // namespace specula::sandbox
