#pragma once
// A cooked distance-cubemap probe: the manifest plus one cube map per layer. On disk each
// layer is a KTX2 cube (RGBA32F for the composite, RGBA16F for an object layer whose every
// value fits a half, docs/formats.md); in memory an N x 6N image, the six faces stacked top to
// bottom in OpenGL order (+X -X +Y -Y +Z -Z, each face's row 0 first), RGB radiance and A the
// Euclidean distance from the probe centre (d_inf where the layer sees nothing).
#include "components/reflection_probe/manifest_fields.h"
#include "engine/image/image.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace specula {

// Largest radiance a cooked probe may hold (layers and sky). 65504 is the largest half
// float: HDR panoramas are commonly stored as half EXR, so no real sky is brighter, and
// anything brighter (1e38 in a tampered file) is garbage rather than light -- it would
// overflow every squared-error metric downstream (PSNR -760 dB). Also keeps any float sum
// of squared errors over a frame finite.
inline constexpr float kMaxRadiance = 65504.f;

struct DistanceProbeLayer {
    std::string name;
    std::vector<std::string> objects; // glTF node names in this layer
    float avgDistance = 0.f;          // d-bar over the valid texels (solid-angle weighted)
    float minDistance = 0.f;
    float maxDistance = 0.f;
    float solidAngle = 0.f;             // steradians covered (texels with a finite distance)
    glm::vec3 boxMin{0.f}, boxMax{0.f}; // probe-local bounds of the layer's geometry
    // The lookup method planned for this layer ("bisection", "avgdist"); a layer made in memory
    // (not read from a manifest, which must name one) is searched by bisection.
    std::string method = "bisection";
    std::array<Image, 6> faces;
    std::string file;     // relative to the manifest
    std::string checksum; // "fnv1a64:<hex>" of the file's bytes
};

// How a probe's composite (layer 0) is stored (docs/formats.md). None: one RGBA float cube.
// Bc6h (`specula-cook bake --compress bc6h`, asset format 3.0): its radiance as BC6H blocks,
// its distance in a one-channel cube of its own (half floats when they hold every distance
// within the lookup's tolerance, distance_compression.h, else float32).
enum class DistanceCompression { None, Bc6h };

struct DistanceProbeAsset {
    std::string manifestPath; // where it was read from (names it in errors); empty if cooked
    ProbeInputs inputs;       // what the cooker baked it from ("inputs"; not recorded: empty)
    glm::vec3 centre{0.f};
    float range = 0.f; // D
    float dInf = 0.f;
    int faceRes = 0;
    glm::vec3 boxMin{0.f}, boxMax{0.f};     // probe-local environment box
    std::vector<DistanceProbeLayer> layers; // [0] composite, then objects near to far
    Image sky;                              // equirectangular panorama (may be empty)
    std::string skyFile, skyChecksum;
    std::string effectPlan; // the cooker's effect plan as JSON text (empty when none)
    // The composite's GGX prefiltered chain (engine/image/ggx_prefilter.h) above level 0 (the
    // composite itself): level i (1 .. size) has faces of max(1, faceRes >> i), RGB
    // prefiltered at perceptual roughness i / size, A the min distance over its footprint
    // (the finite distances of the composite's texels on the same face that overlap the
    // texel; d_inf where none hits). Empty when the bake made none (no glossy reflector); a
    // glossy lookup then prefilters the composite when it loads. On disk: one N_i x 6 N_i
    // float KTX2 cube per level beside the layers (layer_00_ggx_<i>.ktx2, faces stacked as a
    // layer's), listed in the manifest's "glossy": {"levels": [{"file", "checksum",
    // "roughness"}, ...]} (absent when empty).
    std::vector<std::array<Image, 6>> glossyLevels;
    // Bc6h: layers[0].faces hold the decoded radiance and the stored distances (what the GPU
    // samples and the CPU twin reads), `compositeBlocks` the blocks as stored (six faces in
    // order, a face's blocks row by row: what the GPU upload copies), and
    // `halfCompositeDistance` whether the distances are half floats.
    // The glossy levels are BC6H too: glossyBlocks[k] level k + 1's blocks (faces in order),
    // glossyLevels their decoding with A the nearest composite distance under each texel
    // (derived, as the file stores radiance alone).
    DistanceCompression compression = DistanceCompression::None;
    std::vector<std::uint8_t> compositeBlocks;
    std::vector<std::vector<std::uint8_t>> glossyBlocks;
    bool halfCompositeDistance = false;

    int objectLayerCount() const { return int(layers.size()) - 1; }
};

// Most glossy levels a probe may hold: a face of 8192 texels is one texel at level 13.
inline constexpr int kMaxGlossyLevels = 16;

// Solid angle (steradians) of texel (x, y) of an n x n cube face.
double cubeTexelSolidAngle(int x, int y, int n);

// What a layer's faces hold, over the texels that hit something (distance < d_inf): the
// figures the manifest states for the layer, which the reader checks against its image.
struct DistanceLayerContent {
    float minDistance = 0.f, maxDistance = 0.f; // 0, 0 when nothing is hit
    double solidAngle = 0.0;                    // steradians
};
// Measures a layer and checks every texel: RGB finite in [0, kMaxRadiance], distance finite
// in (0, dInf]. Throws Error(file, "radiance" or "distance", ...) naming the face and texel.
DistanceLayerContent measureDistanceLayer(const std::array<Image, 6>& faces, float dInf,
                                          const std::string& file);

// Reads and validates a manifest and its images: format version, every field's type and
// range (centres within kMaxCoordinate, face_res an integer), file checksums, and the
// images' content: float KTX2 cube, every texel valid (measureDistanceLayer), each layer's
// min/max distance and solid angle as the manifest states them, and layer 0 per texel the
// nearest of the object layers; the glossy levels likewise (checksum, float KTX2 cube of
// their size, every texel valid, "roughness" i / L, A the min over the composite under each
// texel), errors naming the image and the field glossy.levels[k] (level k + 1); a manifest
// without "glossy" reads with no glossy levels. Files are read only when regular (no FIFO,
// device or directory). Errors name the file and the field.
// writeDistanceProbe (writer/distance_probe_writer.h, the tools') runs the same content checks
// before writing.
DistanceProbeAsset readDistanceProbe(const std::string& manifestPath);

// readDistanceProbe on a manifest already parsed (the system reads each manifest once; the
// fuzzer parses text in memory): its path names it in errors and locates the images.
DistanceProbeAsset readDistanceProbe(const ProbeManifest& manifest);

} // namespace specula
