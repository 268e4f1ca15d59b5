#pragma once
// specula-sandbox walk: the reflectors move along a path inside the probe's cell while the
// camera swings around them, every frame drawn with the chosen method. Headless it writes
// frame_NNNN.png, contact_sheet.png and frames.csv; with a window it is an interactive
// walkthrough (GLFW + Dear ImGui).
#include "components/reflection_probe/distance/distance_probe.h"
#include "components/reflection_probe/lightfield/lightfield_probe.h"
#include "components/reflection_probe/pem/pem_probe.h"
#include "components/reflection_probe/system/reflection_probe.h"
#include "sandbox/lib/walk/probe_source.h"

#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace specula {

struct WalkOptions {
    std::string input; // scene (.gltf/.glb) or probe manifest (.json)
    std::optional<std::string> scene, sky;
    std::string method = "bisection"; // a row of sandboxMethods()
    float tolerance = 0.01f;          // d_e
    WalkPath path = WalkPath::Orbit;
    // --path camera: the camera follows the scene camera's glTF animation, first key to last,
    // past reflectors that stay put (a PEM baked here follows it too).
    bool cameraPath = false;
    int frames = 60; // headless: frames written; window: 0 = until closed, else exit after N
    bool headless = false;
    bool compare = false; // headless: PSNR of every frame against its ground truth
    std::string outDir = "walk-out";
    int width = 640, height = 480;
    int faceRes = 128; // when a scene is baked here
    // A PEM baked here: its parameter is the reflectors' position on `path` (false: the
    // viewpoint on the camera orbit).
    bool pemByReflector = false;
    bool progress = true;
    // Every reflector's roughness factor (GGX, alpha = r^2; a roughness map multiplies it per
    // pixel), drawn by the glossy lookups and traced by the GGX truth with `glossySamples`
    // a pixel; unset: each reflector's own (its markup or material).
    std::optional<float> roughness;
    int glossySamples = 256;
    // Test mirrors added to the scene wherever it is opened (--add-reflector; the walk
    // functions open it inside an AddedReflectorsScope of these).
    std::vector<AddedReflector> addedReflectors;
    // A cooked manifest baked from another scene (its "inputs" differ): walked with warnings
    // instead of refused.
    bool allowStale = false;
};

// What a walk frame moves: the reflectors along a path and/or the camera along its orbit. A
// viewpoint PEM keeps its reflectors where its maps were inferred; a reflector PEM keeps the
// scene camera still and walks the reflectors along its baked path; every other probe both.
// The camera path (--path camera, or a PEM baked along it) moves the camera alone.
struct WalkMotion {
    bool moveReflectors = true, swingCamera = true;
    WalkPath path = WalkPath::Orbit;
    // A viewpoint PEM baked along the scene camera's animation: the camera follows it
    // (cameraPathView), first key to last, instead of swinging.
    bool cameraPath = false;
};
WalkMotion walkMotion(const ProbeSource& src, const WalkOptions& options);
// The camera of a frame at t: the camera path's (cameraPathView) when the motion follows it,
// else the orbit's at `angle`, `distance` and `heightAbove` (walkCamera).
CameraView walkFrameCamera(const ReflectionScene& scene, const WalkMotion& motion, int width,
                           int height, float t, float angle, float distance, float heightAbove);

// The camera of frame t in [0, 1): the scene camera's distance and height around the probe,
// swung +-23 degrees about its starting angle (a full circle would pass behind columns).
CameraView walkCamera(const ReflectionScene& scene, int width, int height, float t);
CameraView walkCamera(const ReflectionScene& scene, int width, int height, float angle,
                      float distance, float height_);
void walkCameraOrbit(const ReflectionScene& scene, float& angle, float& distance, float& height);

// When the current AddedReflectorsScope adds reflectors: one line each (its node name and
// spec) and one with the scene camera's eye, to `out`.
void logAddedReflectors(const ReflectionScene& scene, int width, int height, std::ostream& out);

// What a scene given to walk is baked into for the options' method.
SourceBake walkSourceBake(const WalkOptions& options);

// Attaches the walk's probe to `scene`: the light-field flavour when src is a light field,
// the PEM flavour (pem-nearest: PemProbe::nearest) when src is a PEM, else the distance flavour
// with the options' method and d_e (each object layer with the cooked plan's method). Throws Error
// naming the manifest when the method is not of its flavour.
ecs::Entity attachWalkProbe(ReflectionScene& scene, const ProbeSource& src,
                            const WalkOptions& options);
// The walk frame t in [0, 1) for the probe's flavour: a PEM's parameter follows t (its
// samples are the viewpoints of walkCamera(t)); other flavours have nothing to set.
void setWalkParameter(ReflectionScene& scene, float t);

// Returns the exit status; throws Error on bad input.
int runWalkHeadless(const WalkOptions& options, std::ostream& out);
int runWalkWindow(const WalkOptions& options, std::ostream& out);

} // namespace specula
