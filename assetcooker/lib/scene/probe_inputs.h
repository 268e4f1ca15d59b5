#pragma once
// What a probe is baked from, as checksums (ProbeInputs): the meshes it can see, the
// reflectors' markup, its settings and the sky. A cooked manifest and a level index record them;
// a re-bake and a tool loading a probe against a scene compare them.
#include "assetcooker/lib/scene/probe_setup.h"
#include "components/reflection_probe/level_index.h"

#include <string>

namespace specula {

class EmbreeScene;

// The checksums a probe is baked from: the meshes within its reach (the environment meshes
// the probe sees along 6 x 32 x 32 directions, those overlapping its proxy, and every
// reflector), each in world space with its material; `options` (the flavour's settings,
// as text) with the volume; the sky file's bytes. `environment`: the scene's Embree BVH
// without the reflectors, built once for all probes of a level.
ProbeInputs levelProbeInputs(ProbeScene& scene, const EmbreeScene& environment,
                             const ProbeVolume& probe, const std::string& options);
// The same for a probe cooked on its own, over the whole scene (every mesh, with its
// material, and every reflector's markup): what its manifest records ("inputs"), and what a
// tool loading it against a scene compares.
ProbeInputs sceneProbeInputs(const ProbeScene& scene, const std::string& options);
// ProbeInputs::sky of a sky image (its file's checksum; "none" for no sky).
std::string skyChecksum(const std::string& skyPath);

} // namespace specula
