#pragma once
// What a game does to use reflection probes in a glTF scene, without the cooker or the
// sandbox: open the scene with its Specula markup and sky, turn the markup into components
// (a ReflectionProbe entity, a Reflector on every reflector mesh), and read what a loader
// needs of a cooked manifest before it loads the asset.
#include "components/reflection_probe/reflection_probe.h"
#include "components/reflection_probe/scene_markup.h"
#include "engine/ecs/registry.h"
#include "engine/image/image.h"
#include "engine/scene/gltf_loader.h"

#include <string>

namespace specula {

// A glTF scene opened for probe work: loaded, world transforms up to date, markup read, sky
// panorama loaded (empty skyPath: a black sky). Throws Error naming the file on bad input.
struct ProbeScene {
    ProbeScene(const std::string& gltfPath, const std::string& skyPath);

    std::string path;
    ecs::Registry registry;
    LoadedScene loaded;
    SceneMarkup markup;
    Image sky;
};

// Creates an entity holding `probe` (named "reflection_probe") and gives every reflector
// mesh of `markup` a Reflector pointing at it. `previous`, when not null, is the probe
// entity this one replaces: it is destroyed first. Returns the new probe entity.
ecs::Entity attachProbeComponents(ecs::Registry& registry, const SceneMarkup& markup,
                                  const ReflectionProbe& probe,
                                  ecs::Entity previous = ecs::kNullEntity);

// What a loader needs of a cooked probe before loading it, from one read of its manifest:
// the flavour that picks the loader, the scene it was baked from and the sky file. The
// asset itself (fields, files, checksums) is validated when it is loaded.
struct CookedProbeFacts {
    std::string flavour; // "distance", "lightfield"
    std::string source;  // the "source" member as written (a path; empty when absent)
    std::string skyFile; // the sky image beside the manifest (a path; empty when none)
};
// Throws Error naming the manifest and the field when it is no Specula probe manifest of
// this format version.
CookedProbeFacts readCookedProbeFacts(const std::string& manifestPath);

} // namespace specula
