#pragma once
// The ReflectionProbe and Reflector components: plain configuration, no GPU state. The
// probe's textures and shaders belong to ReflectionProbeSystem, which (re)creates them when
// a component appears or changes. Adding both to entities of a loaded scene is all it takes.
#include "engine/ecs/entity.h"

#include <string>

#include <glm/vec3.hpp>

namespace specula {

enum class ProbeFlavour { DistanceCubemap, LightFieldSlab };

// How a reflected ray is turned into a texture lookup (distance-cubemap flavour).
enum class LookupMethod {
    Envmap,     // classic: direction only
    BoxProj,    // box-projected cube map (finite box as the environment)
    Bisection,  // per-pixel rectification by bisection (Wang et al. 2012)
    Secant,     // bisection bracket refined by the secant rule
    AvgDist,    // one fetch at x + d-bar l
    Layered,    // object layers near to far, each with its own method, sky last
    Planned,    // whatever the cooked effect plan chose (mode and per-layer methods)
    LightField, // light-field slabs (Yu et al. 2005): needs flavour LightFieldSlab
};

const char* toString(LookupMethod m);
// Parses "envmap", "boxproj", "bisection", "secant", "avgdist", "layered", "plan",
// "lightfield"; false if unknown.
bool parseLookupMethod(const std::string& s, LookupMethod& out);

struct ReflectionProbe {
    ProbeFlavour flavour = ProbeFlavour::DistanceCubemap;
    std::string asset; // cooked manifest.json
    LookupMethod method = LookupMethod::Bisection;
    float errorTolerance = 0.01f; // d_e, metres
    float range = 0.f;            // D, metres; 0 takes the cooked value
    // Layered mode: the method of every object layer (Bisection, Secant or AvgDist; the
    // cooked plan's choice when Envmap is given).
    LookupMethod layerMethod = LookupMethod::Bisection;
    // Light-field flavour: focal-plane disparity in pixels per camera step for all six
    // slabs; NaN or < 0 takes the cooked per-slab optimum. A change re-uploads nothing.
    float disparity = -1.f;
    // Light-field flavour: draw the environment from the light field (eye rays) while the
    // eye is inside the cell, instead of rasterising it.
    bool lightFieldBackground = false;

    bool operator==(const ReflectionProbe&) const = default;
};

struct Reflector {
    ecs::Entity probe;      // which probe it reflects
    float fresnelF0 = -1.f; // < 0: perfect mirror; otherwise Schlick with this F0

    bool operator==(const Reflector&) const = default;
};

} // namespace specula
