#pragma once
// What walk and bench start from: a scene (.gltf/.glb, baked here into a probe) or a cooked
// manifest (its scene found through the manifest's "source"). Plus the small helpers both
// subcommands share: the reflector path inside the cell.
#include "assetcooker/lib/bake/cook.h"
#include "components/reflection_probe/walk_path.h"
#include "engine/image/image.h"
#include "sandbox/lib/render/reflection_scene.h"
#include "sandbox/lib/render/scene_cook.h"

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
    // A PEM's parameter (its manifest's "parameter_kind" and "path"): "reflector" moves the
    // reflectors along the path before a still camera; "viewpoint" swings the camera along
    // the orbit past still reflectors.
    bool pemByReflector = false;
    WalkPath pemPath = WalkPath::Orbit;
    bool pemCameraPath = false; // "path": "camera": the viewpoint follows the camera animation
    int pemImageWidth = 0, pemImageHeight = 0; // the frame its maps fit; 0: not recorded
};

// What resolveProbeSource bakes from a scene.
enum class SourceBake { Distance, LightField, Pem };

// What resolveProbeSource bakes: the probe's cube faces, the frame it will be drawn at (a
// PEM is inferred for those pixels) and, for a PEM, what its parameter moves: the viewpoint
// along the camera orbit, or the reflectors along `path`.
struct SourceBakeSize {
    int faceRes = 128;
    int width = 640, height = 480;
    bool pemByReflector = false;
    WalkPath path = WalkPath::Orbit;
    bool cameraPath = false; // a viewpoint PEM along the scene camera's animation (--path camera)
};

// `input`: a scene or a manifest.json. `sceneOverride`: the scene to use with a manifest
// (else its "source", relative to the working directory or to the manifest's folder).
// A scene is baked with Embree into `bakeDir` (replaced): a distance probe with size.faceRes,
// a light field (16 cameras of 32^2 pixels a slab) or a PEM (sandboxPemSettings(size)). Throws
// Error naming the file on bad input. `log`: the bake's warnings (null: dropped).
// A manifest that records its inputs (cooked since format 2.2) must fit the scene: its meshes,
// materials and reflectors, and the sky when `skyOverride` is given; what differs is listed
// on `log` and refused as Error(manifest, "inputs") unless `allowStale` (then warnings).
ProbeSource resolveProbeSource(const std::string& input,
                               const std::optional<std::string>& sceneOverride,
                               const std::optional<std::string>& skyOverride,
                               const std::string& bakeDir, SourceBakeSize size, bool showProgress,
                               SourceBake bake = SourceBake::Distance, std::ostream* log = nullptr,
                               bool allowStale = false);

// The PEM the sandbox bakes: `samples` viewpoints t = k/samples on the walk's camera orbit,
// one ray per pixel of the frame it is drawn at, size.faceRes^2 faces.
PemCookSettings sandboxPemSettings(SourceBakeSize size, int samples = 8);

// Bakes the distance probe of a loaded scene into `dir` through the cooking API (cookProbe);
// returns the seconds it took. planned: the layers and methods of the effect plan (else one
// layer per object). `log`: the cook's warnings (null: dropped).
double bakeDistanceProbeInto(ReflectionScene& scene, const std::string& dir, int faceRes,
                             bool showProgress, bool planned = false, std::ostream* log = nullptr);

} // namespace specula
