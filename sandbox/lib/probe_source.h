#pragma once
// What walk and bench start from: a scene (.gltf/.glb, baked here into a probe) or a cooked
// manifest (its scene found through the manifest's "source"). Plus the small helpers both
// subcommands share: the reflector path inside the cell.
#include "assetcooker/lib/cook.h"
#include "engine/image/image.h"
#include "sandbox/lib/reflection_scene.h"

#include <memory>
#include <optional>
#include <ostream>
#include <string>

namespace specula {

struct ProbeSource {
    std::string scenePath;
    std::string skyPath;
    std::string manifest;   // cooked distance probe
    double bakeSeconds = 0; // 0 when a cooked manifest was given
    bool baked = false;
    bool lightField = false; // the manifest is a light-field probe
    bool pem = false;        // the manifest is a parameterized environment map
};

// What resolveProbeSource bakes from a scene.
enum class SourceBake { Distance, LightField, Pem };

// `input`: a scene or a manifest.json. `sceneOverride`: the scene to use with a manifest
// (else its "source", relative to the working directory or to the manifest's folder).
// A scene is baked with Embree into `bakeDir` (replaced): a distance probe with `faceRes`, a
// light field (16 cameras of 32^2 pixels a slab) or a PEM (sandboxPemSettings()). Throws
// Error naming the file on bad input. `log`: the bake's warnings (null: dropped).
ProbeSource resolveProbeSource(const std::string& input,
                               const std::optional<std::string>& sceneOverride,
                               const std::optional<std::string>& skyOverride,
                               const std::string& bakeDir, int faceRes, bool showProgress,
                               SourceBake bake = SourceBake::Distance, std::ostream* log = nullptr);

// The PEM the sandbox bakes: 8 viewpoints t = k/8 on the walk's camera orbit, 2x2 rays a
// pixel; walk bakes 32^2 faces, the bench 64^2 (about 1.5 s on the room).
PemCookSettings sandboxPemSettings(int faceRes = 32);

// Bakes the distance probe of a loaded scene into `dir` through the cooking API (cookProbe);
// returns the seconds it took. planned: the layers and methods of the effect plan (else one
// layer per object). `log`: the cook's warnings (null: dropped).
double bakeDistanceProbeInto(ReflectionScene& scene, const std::string& dir, int faceRes,
                             bool showProgress, bool planned = false, std::ostream* log = nullptr);

// The cooking API (cookProbe) on the sandbox's scene: `flavour`'s probe into `dir`.
CookResult cookSceneInto(ReflectionScene& scene, const std::string& dir, const CookFlavour& flavour,
                         bool showProgress, std::ostream* log);

// Walk paths: where the reflectors are at time t in [0, 1), as an offset from their authored
// position. Every path stays within 0.2 cell sizes of it on each axis, inside the cell.
enum class WalkPath { Orbit, Line, Figure8 };
bool parseWalkPath(const std::string& s, WalkPath& out);
const char* toString(WalkPath p);
glm::vec3 walkOffset(WalkPath path, float t, float amplitude);

} // namespace specula
