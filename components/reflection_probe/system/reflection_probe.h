#pragma once
// The components every probe flavour shares: plain configuration, no GPU state. A probe
// entity holds a ReflectionProbe (which cooked asset) and, optionally, its flavour's
// settings component (distance/distance_probe.h, lightfield/lightfield_probe.h; defaults
// when absent); the asset's manifest names the flavour. ReflectionProbeSystem owns the GPU
// side and (re)builds it when a component appears or changes.
#include "engine/ecs/entity.h"
#include "engine/image/image.h"

#include <memory>
#include <string>

namespace specula {

struct ReflectionProbe {
    std::string asset; // cooked manifest.json

    bool operator==(const ReflectionProbe&) const = default;
};

struct Reflector {
    ecs::Entity probe;      // which probe it reflects
    float fresnelF0 = -1.f; // < 0: perfect mirror; otherwise Schlick with this F0
    float roughness = 0.f;  // GGX (alpha = roughness^2); 0 = a mirror
    // Multiplies `roughness` per pixel where set (its G channel at the mesh's TEXCOORD_0, the
    // glTF metallic-roughness texture; reflector_roughness.h); null: uniform roughness.
    std::shared_ptr<const Image> roughnessMap;

    bool operator==(const Reflector&) const = default;
};

} // namespace specula
