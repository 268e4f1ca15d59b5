#pragma once
// The distance-cubemap flavour's settings component and its method table. A probe entity
// whose manifest is "distance" may hold a DistanceProbe (defaults when it does not).
#include "components/reflection_probe/method_label.h"

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace specula {

// How a reflected ray is turned into a texture lookup.
enum class DistanceMethod {
    Envmap,    // classic: direction only
    BoxProj,   // box-projected cube map (finite box as the environment)
    Bisection, // per-pixel rectification by bisection (Wang et al. 2012)
    Secant,    // bisection bracket refined by the secant rule
    AvgDist,   // one fetch at x + d-bar l
    March,     // linear march + secant refinement (Szirmay-Kalos et al. 2005), the peer
    Layered,   // object layers near to far, each with its own method, sky last
    Planned,   // whatever the cooked effect plan chose (mode and per-layer methods)
};

struct DistanceProbe {
    // What the cooker planned for this probe (an unplanned asset: the method each layer was
    // cooked with), so a probe built from a cooked asset draws as the plan measured it.
    DistanceMethod method = DistanceMethod::Planned;
    float errorTolerance = 0.01f; // d_e, metres
    float range = 0.f;            // D, metres; 0 takes the cooked value
    // Layered mode: the method of every object layer (a per-layer row of the table; the
    // cooked plan's choice when Envmap is given).
    DistanceMethod layerMethod = DistanceMethod::Bisection;

    bool operator==(const DistanceProbe&) const = default;
};

// One row per method: everything that names, compiles, plots or explains it. Adding a method
// is a row here, a kMethod* value and its branch in shaders/distance_lookup.glsl.h.
struct DistanceMethodInfo {
    DistanceMethod method;
    MethodLabel label;     // name (CLI, manifests, the effect plan, bench rows), colour, help
    int glslIndex;         // kMethod* the shader switches on; -1 for the modes
    std::uint32_t feature; // permutation bit; 0 for the modes
    const char* define;    // the GLSL define that compiles the method in (null for modes)
    bool perLayer;         // may be an object layer's method (layered mode, the plan)
    bool usesTolerance;    // its accuracy depends on d_e (the bench sweeps it)
};

// Permutation bits that are not methods.
inline constexpr std::uint32_t kFeatureLayers = 1u << 5;
inline constexpr std::uint32_t kFeatureFresnel = 1u << 6;
// A rough reflector (Reflector::roughness > 0): the composite's GGX prefiltered chain read at
// the hit (shaders/distance_glossy_lookup.glsl.h). Per reflector, like Fresnel.
inline constexpr std::uint32_t kFeatureGlossy = 1u << 7;
// The composite is stored compressed (DistanceCompression::Bc6h): radiance sampled from a BC6H
// array, distance from an array of its own (shaders/distance_probe_gpu.glsl,
// COMPRESSED_COMPOSITE). Per probe, from its asset.
inline constexpr std::uint32_t kFeatureCompressedComposite = 1u << 9;
// The method bits are 1 << 0..4 and 1 << 8 (march, added after the feature bits above).

inline constexpr std::array<DistanceMethodInfo, 8> kDistanceMethods = {{
    {DistanceMethod::Envmap,
     {"envmap", {0.90f, 0.10f, 0.08f}, "classic environment map: direction only, no parallax"},
     0,
     1u << 0,
     "HAS_ENVMAP",
     false,
     false},
    {DistanceMethod::BoxProj,
     {"boxproj", {0.95f, 0.45f, 0.02f}, "box-projected cube map: the environment as a box"},
     1,
     1u << 1,
     "HAS_BOXPROJ",
     false,
     false},
    {DistanceMethod::Bisection,
     {"bisection", {0.90f, 0.90f, 0.10f}, "per-pixel rectification by bisection to d_e"},
     2,
     1u << 2,
     "HAS_BISECTION",
     true,
     true},
    {DistanceMethod::Secant,
     {"secant", {0.10f, 0.70f, 0.15f}, "the bisection bracket refined by the secant rule"},
     3,
     1u << 3,
     "HAS_SECANT",
     true,
     true},
    {DistanceMethod::AvgDist,
     {"avgdist", {0.10f, 0.30f, 1.00f}, "one fetch at the layer's average distance"},
     4,
     1u << 4,
     "HAS_AVGDIST",
     true,
     false},
    {DistanceMethod::March,
     {"march", {0.95f, 0.30f, 0.65f}, "linear march + secant refinement (Szirmay-Kalos 2005)"},
     5,
     1u << 8,
     "HAS_MARCH",
     true,
     true},
    {DistanceMethod::Layered,
     {"layered", {0.55f, 0.20f, 0.90f}, "object layers near to far, each with its method"},
     -1,
     0,
     nullptr,
     false,
     true},
    {DistanceMethod::Planned,
     {"plan", {0.10f, 0.85f, 0.85f}, "whatever the cooked effect plan chose"},
     -1,
     0,
     nullptr,
     false,
     true},
}};

const DistanceMethodInfo& info(DistanceMethod m);
const char* toString(DistanceMethod m);
// Null when `name` is no method of the table.
const DistanceMethodInfo* findDistanceMethod(std::string_view name);
// "envmap, boxproj, ..." (for messages and --help).
std::string distanceMethodNames();

} // namespace specula
