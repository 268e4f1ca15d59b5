#pragma once
// The cooker side of parameterized environment maps (Hakura, Snyder, Lengyel 2001, §3-5;
// docs/design.md §5b): at each sample of the parameter (the viewpoint along the walk's orbit),
// Embree traces the reflector pixels the camera sees, the ray tracer's FULL multi-bounce radiance
// along each reflected ray is the target (self- and inter-reflections included: what a plain
// environment map cannot hold), and inferPemMap fits the map the lookup reproduces it best
// with. The maps of all samples make one PemAsset.
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

// The PEM flavour's cook settings (cook.h's CookFlavour). Parameter "viewpoint": the camera
// moves along the walk's camera orbit (path "orbit", walkOrbitCameraView), the reflectors stay
// put. Parameter "reflector": the reflectors move along the walk path "orbit", "line" or
// "figure8" (walk_path.h) before the scene camera (the orbit at t = 0): the paper's "relative
// motion of objects". Path "camera" (a glTF camera animation) is refused: not read yet.
struct PemCookSettings {
    int samples = 8;     // parameter samples t = k / samples, k = 0 .. samples-1; 1 .. 1024
    int faceRes = 128;   // 1 .. 1024
    int supersample = 1; // rays per pixel side, 1 .. 16
    float regularisation = 0.02f;
    // The map's geometry: "box" (the ray meets the environment's bounding box) or "distance"
    // (the ray is rectified against the environment's distance cube at the centre, traced
    // by Embree at faceRes: objects inside the box sit where they are, from any viewpoint).
    std::string geometry = "distance";
    // Weight of the rows pulling every texel towards the radiance captured at the centre
    // (the distance geometry's capture): texels the camera does not see fall back to what
    // an ordinary cube map holds there instead of to their neighbours alone. 0: no prior.
    // 0.05 measured on the room (320x240, 8 viewpoints): half-way 18.4 -> 19.7 dB full,
    // on the samples 46.3 -> 41.3 dB.
    float priorWeight = 0.05f;
    std::string parameter = "viewpoint";
    std::string path = "orbit";
    // The camera image the samples are traced through: a PEM is inferred for the pixels the
    // renderer draws, so bake at the frame size it will be drawn at (the walk's default
    // 640 x 480). With supersample 1 the rows are exactly the rasteriser's pixel centres.
    int imageWidth = 640, imageHeight = 480;
    // The local layer (pem_layers.h): "auto" adds it when some reflector ray off the hull
    // meets its own reflector again at any sample (measured), "on" always, "off" never.
    std::string localLayer = "auto";
    int localFaceRes = 0; // its cube's face resolution; 0: faceRes
    // The local sphere: "bound" (the off-hull reflector points' bounding sphere) or "fit" (the
    // least-squares sphere through them: a bowl's own sphere; fitPemLocalSphere). Measured on
    // the bowl room (N=8, on / half-way dB against the full truth, cooker's fit): 160x120 with
    // 64^2 faces bound 29.3 / 13.1, fit 28.9 / 13.3 (one map 28.2 / 13.1); 120x90 with 24^2
    // faces bound 28.0 / 13.8, fit 24.4 / 13.3 (one map 21.0 / 12.9). Rays from different
    // points that meet the bowl at one point see different things there; the exact sphere
    // sends them all to one texel, a sphere off the bowl's centre spreads them.
    std::string localSphere = "bound";
    // MIP levels of the distant maps, all inferred together (PemInferOptions::mipLevels), 1 ..
    // PemMap::maxLevels(faceRes); 1: level 0 alone, as before MIP levels existed.
    int mipLevels = 1;
    // The rendering matrix's data rows (PemRows), against the antialiased image (each
    // displayed pixel's mean radiance over its sub-rays, Hakura §4): "pixel", the mean of
    // the sub-rays' lookups; "centre" (an odd supersample), the lookup of the pixel's centre
    // ray, as the rasteriser draws it; or "subray", one row per traced ray against its own
    // radiance (the default: the bench's truth is one ray a pixel, against which centre rows
    // lose on level 0 while they win against the antialiased image, pem_pixel_rows_test).
    // All the same with supersample 1.
    std::string rows = "subray";
    // Keep the inferred texels >= 0 by active-set re-solves (PemInferOptions::nonNegative)
    // instead of clamping the unconstrained solution afterwards. On by default: at 256² the
    // full PSNR gains 0-0.3 dB at level 0 and 1.6-3.1 dB with inferred MIPs, the cooker's own
    // fit 10-15 dB, for 1.5-1.9x the inference (CHANGELOG.md, "PEM texels bounded ... at 256²").
    bool nonNegative = true;
    // Distance geometry: rows for the lookups the display's rounding reaches
    // (pem_rounding_rows.h; PemInferOptions::roundingReach), metres and radians. 0: off.
    float roundingReach = 1e-4f;
    // How the maps are stored: "none" (float RGB) or "bc6h" (every level of every sample map in
    // BC6H, pem/writer/pem_compression.h), encoded after the inference.
    std::string compression = "none";
};

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

// Throws Error naming the field ("samples", "face_res", "supersample", "regularisation",
// "image_size", "geometry", "prior_weight" (needs the distance geometry), "parameter", "path"
// (orbit or camera for the viewpoint, a walk path for the reflector),
// "local_layer", "local_face_res", "local_sphere", "mip_levels", "rows").
void validatePemCookSettings(const PemCookSettings& s, const std::string& file);

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
