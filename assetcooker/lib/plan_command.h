#pragma once
// `specula-cook plan`: prints the effect plan of a scene's probe without baking.
#include <ostream>
#include <span>
#include <string>
#include <string_view>

namespace specula::cook {

extern const std::string_view kPlanUsage;
int runPlan(std::span<const std::string> args, std::ostream& out, std::ostream& err);

} // namespace specula::cook
