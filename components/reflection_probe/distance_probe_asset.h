#pragma once
// A cooked distance-cubemap probe: the manifest plus one cube map per layer. On disk each
// layer is a float EXR of N x 6N pixels, the six faces stacked top to bottom in OpenGL order
// (+X -X +Y -Y +Z -Z, each face's row 0 first), RGB radiance and A the Euclidean distance
// from the probe centre (d_inf where the layer sees nothing).
#include "engine/image/image.h"

#include <array>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace specula {

inline constexpr int kProbeFormatVersion = 1;

struct DistanceProbeLayer {
    std::string name;
    std::vector<std::string> objects; // glTF node names in this layer
    float avgDistance = 0.f;          // d-bar over the valid texels (solid-angle weighted)
    float minDistance = 0.f;
    float maxDistance = 0.f;
    float solidAngle = 0.f;             // steradians covered (texels with a finite distance)
    glm::vec3 boxMin{0.f}, boxMax{0.f}; // probe-local bounds of the layer's geometry
    std::string method; // planned lookup method for this layer ("bisection", "avgdist")
    std::array<Image, 6> faces;
    std::string file;     // relative to the manifest
    std::string checksum; // "fnv1a64:<hex>" of the file's bytes
};

struct DistanceProbeAsset {
    glm::vec3 centre{0.f};
    float range = 0.f; // D
    float dInf = 0.f;
    int faceRes = 0;
    glm::vec3 boxMin{0.f}, boxMax{0.f};     // probe-local environment box
    std::vector<DistanceProbeLayer> layers; // [0] composite, then objects near to far
    Image sky;                              // equirectangular panorama (may be empty)
    std::string skyFile, skyChecksum;
    std::string effectPlan; // the cooker's effect plan as JSON text (empty when none)

    int objectLayerCount() const { return int(layers.size()) - 1; }
};

// FNV-1a 64-bit of a file's bytes as "fnv1a64:<16 hex digits>". Throws Error naming the file.
std::string fileChecksum(const std::string& path);

// Writes DIR/manifest.json and the layer EXRs. Everything goes to a sibling temporary folder
// first and replaces DIR by rename, so an interrupted or failed write leaves DIR as it was.
void writeDistanceProbe(const DistanceProbeAsset& asset, const std::string& dir,
                        const std::string& sourceScene);

// Reads and validates a manifest and its images: format version, every field's type and
// range, file checksums. Errors name the file and the field.
DistanceProbeAsset readDistanceProbe(const std::string& manifestPath);

// readDistanceProbe on manifest text already in memory (the fuzzer's entry point):
// `manifestPath` names the manifest in errors and locates the images beside it.
DistanceProbeAsset parseDistanceProbe(const std::string& manifestText,
                                      const std::string& manifestPath);

} // namespace specula
