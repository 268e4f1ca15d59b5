#include "sandbox/lib/cli/added_reflector_flag.h"

#include "engine/core/error.h"

namespace specula::sandbox {

namespace {

constexpr const char* kAddReflectorHelp =
    "SPEC: drop a test mirror (a perfect mirror) into the scene; repeatable. "
    "sphere:x,y,z,r is a sphere of radius r centred at x,y,z; box:x,y,z,sx,sy,sz an "
    "axis-aligned box centred at x,y,z with edge lengths sx,sy,sz (metres, world space), "
    "e.g. --add-reflector sphere:0,1.2,0,0.3 --add-reflector box:1,0.5,-1,0.4,1,0.4. "
    "Without a camera node the camera is placed in free space where it sees the reflectors";

// Each value a sphere or box spec (parseAddedReflector).
CLI::Validator addedReflectorText() {
    return CLI::Validator(
        [](std::string& text) -> std::string {
            try {
                parseAddedReflector(text);
                return {};
            } catch (const UsageError& e) {
                return e.message();
            }
        },
        "SPEC");
}

} // namespace

CLI::Option* addReflectorOption(CLI::App* sub, std::vector<std::string>& specs,
                                const std::string& note) {
    return sub->add_option("--add-reflector", specs, std::string(kAddReflectorHelp) + note)
        ->allow_extra_args(false)
        ->check(addedReflectorText());
}

std::vector<AddedReflector> parseAddedReflectors(const std::vector<std::string>& specs) {
    std::vector<AddedReflector> out;
    for (const std::string& s : specs)
        out.push_back(parseAddedReflector(s));
    return out;
}

} // namespace specula::sandbox
