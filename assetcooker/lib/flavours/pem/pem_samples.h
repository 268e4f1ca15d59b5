#pragma once
// The cooker side of parameterized environment maps (Hakura, Snyder, Lengyel 2001, §3-5;
// docs/design.md §5b): at each sample of the parameter (the viewpoint along the walk's orbit),
// Embree traces the reflector pixels the camera sees, the ray tracer's FULL multi-bounce radiance
// along each reflected ray is the target (self- and inter-reflections included: what a plain
// environment map cannot hold), and inferPemMap fits the map the lookup reproduces it best
// with. The maps of all samples make one PemAsset.
#include "assetcooker/lib/flavours/pem/pem_cook_settings.h"
#include "assetcooker/lib/flavours/pem/pem_infer.h"
#include "assetcooker/lib/scene/probe_setup.h"
#include "components/reflection_probe/pem/pem_asset.h"
#include "components/reflection_probe/pem/system/pem_hull.h"

#include <functional>
#include <optional>
#include <string>
#include <unordered_map>
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
    // Also trace what the two-layer maps need (pem_layers.h): PemSample::distant, selfHit,
    // and onHull from `hull` (the flags of each reflector entity, pemHullFlags; a reflector
    // it lacks counts as all hull). false: those fields keep their defaults.
    bool layers = false;
    const std::unordered_map<ecs::Entity, PemHullFlags>* hull = nullptr;
    // The tracer's registry: set, each sample gets its pixel's footprint (PemSample::dxdX,
    // dxdY, dldX, dldY), its quad partners shaded on its own triangle's plane as the GPU
    // shades them (triangle_plane.h). With supersample s > 1 the partners are the sub-pixel
    // grid's, the differences scaled by s: the displayed pixel is s sub-pixels wide. Null:
    // zero footprints (MIP level 0).
    const ecs::Registry* registry = nullptr;
};

// One PemSample per (sub-pixel) primary ray that hits a reflector of the markup: x = hit -
// probeCentre, l = the mirror direction about the shading normal (turned to the viewer, as
// the tracer does), target = the tracer's radiance along l from just off the surface,
// pixel = the camera pixel it is a sub-ray of, centre = whether it is that pixel's middle
// sub-ray (PemSample::pixel, centre; at an odd supersample the pixel's own centre ray, whose
// footprint is then the displayed pixel's quad as at supersample 1).
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

// How well one sample's map fits, measured by the cooker against the ray tracer on the
// reflector rays (no Fresnel: the maps hold incident radiance). PSNR with peak 1 over RGB.
struct PemSampleFit {
    float parameter = 0.f;
    int rays = 0;            // reflector rays traced at the sample's viewpoint: its data rows
    int unseenTexels = 0;    // texels no ray reads: filled by the smoothness rows alone
    int roundingRows = 0;    // copies of rays the display's rounding can move (roundingReach)
    double inferSeconds = 0; // building the rendering matrix, solving, measuring
    double psnrOn = 0;       // at its own viewpoint (on the manifold); NaN: no PSNR
    // Half-way to the next sample (across the wrap on the orbit): the blend of the two maps,
    // as the runtime draws it, against the tracer at that viewpoint (off the manifold). NaN
    // for the last sample of an open path (the camera path): nothing lies past it.
    double psnrOff = 0;
    // Layered bakes: the share of this sample's rays that meet their own reflector again
    // (off the hull), and whether the asset got a local layer. Single-map bakes: 0, false.
    double selfHitFraction = 0;
    bool localLayer = false;
    // The camera saw no reflector pixel at this sample: it has no map in the asset (rays 0).
    bool leftOut = false;
};

// What the cooking API gives every baker: the probe centre, a progress callback (fraction of
// the parameter samples done), a cancel poll, where placement warnings go.
struct PemCookHooks {
    std::optional<glm::vec3> centre; // default: markupProbeCentre
    std::function<void(double)> progress;
    std::function<bool()> cancelled;
    std::vector<std::string>* warnings = nullptr;
    std::vector<PemSampleFit>* fits = nullptr; // one per sample, in order; measured when set
};

// The map box, probe-local: the environment's bounds (every non-reflector mesh) grown to hold
// the markup's cell around the centre, so every reflector point lies inside it; the cell
// alone when the scene has no environment mesh (a sky-only scene).
Aabb pemMapBox(const ProbeScene& scene, glm::vec3 centre);

// Every parameter sample is independent: its scene state at t = pemSampleParameter (the
// viewpoint walkOrbitCameraView(t) or, on the camera path, cameraPathView(t), or the reflectors at
// walkOffset(path, t) with the registry's transforms restored afterwards), its samples
// (tracePemSamples, full ground truth), its map (inferPemMap). Validates first. Every sample is
// traced before any is inferred: the local layer (localLayer "auto": some off-hull ray of some
// sample meets its own reflector again) and its sphere are the asset's, and then each sample's maps
// are the two layers (inferPemLayers, the rays' layer fields traced with every reflector's
// pemHullFlags). With hooks.fits, each sample's fit is measured on and off the manifold (one more
// trace per sample, half-way to the next). A cancel polled between samples throws Error naming the
// scene and "cancelled".
PemAsset cookPemAsset(ProbeScene& scene, const PemCookSettings& s, const PemCookHooks& hooks);

// PSNR (peak 1, over RGB) of `radiance(sample)` against the samples' targets, over the data
// rows `rows` makes of them (pemRowsRms: Pixel and Centre compare against each pixel's mean
// over its sub-rays, the antialiased image); 120 dB when they agree exactly; NaN (no PSNR,
// print it with formatPsnr) when there is no row, or when the targets are all black and
// the radiance agrees (nothing was measured: see ImageStats).
double pemSamplesPsnr(const PemSamples& samples,
                      const std::function<glm::vec3(const PemSample&)>& radiance,
                      PemRows rows = PemRows::SubRay);

// The settings' rows as the inference takes them.
PemRows pemRows(const PemCookSettings& s);

// Whether the settings' path is a closed loop (every walk path) or open (the camera path).
bool pemPathClosed(const PemCookSettings& s);
// Sample k's parameter: k / samples on a closed loop, k / (samples - 1) on an open path (0 for
// a single sample), so an open path's two ends are both samples.
float pemSampleParameter(const PemCookSettings& s, int k);

} // namespace specula
