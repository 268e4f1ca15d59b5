#pragma once
// The parameterized-environment-map flavour's settings component and its method table. A
// probe entity whose manifest is "pem" may hold a PemProbe (defaults when it does not).
#include "components/reflection_probe/method_label.h"

#include <array>

namespace specula {

struct PemProbe {
    // Where on the cooked parameter axis the current frame is, in [0, 1] (the viewpoint or
    // the reflector along the asset's walk path); the game or the sandbox sets it each
    // frame. An edit uploads the parameter block only.
    float parameter = 0.f;
    bool nearest = false; // the nearest sample alone instead of the blend of the two nearest

    bool operator==(const PemProbe&) const = default;
};

struct PemMethodInfo {
    MethodLabel label; // name (CLI, bench rows), plot colour, help
    bool nearest;      // the PemProbe::nearest it selects
};

inline constexpr std::array<PemMethodInfo, 2> kPemMethods = {{
    {{"pem",
      {0.35f, 0.95f, 0.55f},
      "parameterized environment maps: the two samples nearest the parameter, blended"},
     false},
    {{"pem-nearest",
      {0.20f, 0.60f, 0.35f},
      "parameterized environment maps: the nearest sample alone"},
     true},
}};

} // namespace specula
