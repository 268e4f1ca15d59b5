#pragma once
// `specula-cook bake`: glTF scene in, cooked probe folder out.
#include <ostream>
#include <span>
#include <string>
#include <string_view>

namespace specula::cook {

extern const std::string_view kBakeUsage;
int runBake(std::span<const std::string> args, std::ostream& out, std::ostream& err);

} // namespace specula::cook
