#pragma once
// The cooker side of parameterized environment maps (Hakura, Snyder, Lengyel 2001, §3-5;
// DESIGN §5b): at each sample of the parameter (the viewpoint along the walk's orbit), Embree
// traces the reflector pixels the camera sees, the ray tracer's FULL multi-bounce radiance
// along each reflected ray is the target (self- and inter-reflections included: what a plain
// environment map cannot hold), and inferPemMap fits the map the lookup reproduces it best
// with. The maps of all samples make one PemAsset.
#include "assetcooker/lib/pem_infer.h"
#include "components/reflection_probe/pem/pem_asset.h"
#include "components/reflection_probe/probe_setup.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace specula {

struct PemSampleOptions {
    // supersample x supersample rays per pixel, at the sub-pixel centres (no jitter): exactly
    // the pixel-centre rays of the camera with its image supersample times larger.
    int supersample = 2; // 1 .. 16
    // false: the target is the full ground truth (up to four bounces, every mirror visible);
    // true: reflected rays see the environment only (TraceOptions::environmentOnly), what a
    // cube map captured at the probe centre can represent.
    bool environmentOnly = false;
};

// One PemSample per (sub-pixel) primary ray that hits a reflector of the markup: x = hit -
// probeCentre, l = the mirror direction about the shading normal (turned to the viewer, as
// the tracer does), target = the tracer's radiance along l from just off the surface.
// Traced in parallel rows, concatenated in row order: the same samples every run. Throws
// Error naming the scene and "specula_reflector" (the markup has no reflector), "camera"
// (the camera sees no reflector pixel) or "supersample".
PemSamples tracePemSamples(ProbeScene& scene, const CameraView& camera, glm::vec3 probeCentre,
                           const PemSampleOptions& o);
// The same with a tracer already built (groundTruthOptions(scene, ...)); `file` names the
// scene in errors.
PemSamples tracePemSamples(const GroundTruthTracer& tracer, const CameraView& camera,
                           glm::vec3 probeCentre, const PemSampleOptions& o,
                           const std::string& file);

// The PEM flavour's cook settings (cook.h's CookFlavour). Only the parameter "viewpoint"
// along the path "orbit" (the walk's camera orbit, walkOrbitCameraView) is implemented.
struct PemCookSettings {
    int samples = 8;     // parameter samples t = k / samples, k = 0 .. samples-1; 1 .. 1024
    int faceRes = 32;    // 1 .. 1024
    int supersample = 2; // rays per pixel side, 1 .. 16
    float regularisation = 0.02f;
    std::string parameter = "viewpoint";
    std::string path = "orbit";
    int imageWidth = 160, imageHeight = 120; // the camera image the samples are traced through
};

// Throws Error naming the field ("samples", "face_res", "supersample", "regularisation",
// "image_size", "parameter", "path": the last two say they are not implemented yet).
void validatePemCookSettings(const PemCookSettings& s, const std::string& file);

// What the cooking API gives every baker: the probe centre, a progress callback (fraction of
// the parameter samples done), a cancel poll, where placement warnings go.
struct PemCookHooks {
    std::optional<glm::vec3> centre; // default: markupProbeCentre
    std::function<void(double)> progress;
    std::function<bool()> cancelled;
    std::vector<std::string>* warnings = nullptr;
};

// The map box, probe-local: the environment's bounds (every non-reflector mesh) grown to hold
// the markup's cell around the centre, so every reflector point lies inside it; the cell
// alone when the scene has no environment mesh (a sky-only scene).
Aabb pemMapBox(const ProbeScene& scene, glm::vec3 centre);

// Every parameter sample is independent: its viewpoint walkOrbitCameraView(t = k / samples),
// its samples (tracePemSamples, full ground truth), its map (inferPemMap). Validates first.
// A cancel polled between samples throws Error naming the scene and "cancelled".
PemAsset cookPemAsset(ProbeScene& scene, const PemCookSettings& s, const PemCookHooks& hooks);

} // namespace specula
