#pragma once
// --add-reflector SPEC (repeatable), as walk, bench and level take it: the option with its
// help and check, and the parsed list (assetcooker/lib/scene/added_reflector.h).
#include "assetcooker/lib/scene/added_reflector.h"

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace specula::sandbox {

// Adds --add-reflector to `sub`, collecting the specs into `specs`; `note` ends the help.
CLI::Option* addReflectorOption(CLI::App* sub, std::vector<std::string>& specs,
                                const std::string& note = "");
std::vector<AddedReflector> parseAddedReflectors(const std::vector<std::string>& specs);

} // namespace specula::sandbox
