#pragma once
// A cooked parameterized-environment-map probe (Hakura, Snyder, Lengyel 2001): one map
// (box or distance geometry) per sample of a one-dimensional parameter (where the viewer or the
// reflector is along a walk path), the maps inferred offline so that the lookup reproduces the
// ray-traced reflection at that sample. At run time the two samples nearest the current parameter
// are blended (pem_blend.h).
//
// On disk: manifest.json ("flavour": "pem") plus one float KTX2 cube per sample, N x 6N, faces
// +X -X +Y -Y +Z -Z top to bottom (OpenGL face orientation, each face's row 0 first), RGB
// linear radiance: texel (face, i, j) of the PemMap is pixel (i, face * N + j). A map of
// distance geometry ("geometry": "distance") adds distance.ktx2, M x 6M in the same layout,
// one channel: the environment's distance from the centre per texel of its own cube. An asset
// with a local layer ("local_layer": face resolution, sphere) adds local_NN.ktx2 per sample,
// L x 6L in the same layout, RGBA: premultiplied local radiance and coverage alpha. An asset
// with MIP levels ("mip_levels": L > 1) adds sample_NN_mipK.ktx2 per sample and level k >= 1,
// max(N >> k, 1) x 6 max(N >> k, 1) in the same layout, listed in the sample's "mips".
// A compressed asset ("compression": "bc6h", asset format 3.2) stores every level of every
// sample map as a BC6H KTX2 cube instead (vkFormat 131, each face's blocks row by row); the
// local layer (coverage alpha) and the distance cube stay float.
#include "components/reflection_probe/manifest_fields.h"
#include "components/reflection_probe/pem/pem_lookup_cpu.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace specula {

// How the distant maps are stored: float RGB, or BC6H blocks (1 byte a texel against the GPU's
// 16 of RGBA32F; `specula-cook bake --flavour pem --compress bc6h`).
enum class PemCompression { None, Bc6h };

struct PemSampleMap {
    float parameter = 0.f;      // where on the parameter axis this map was inferred, in [0, 1]
    PemMap map;                 // faceRes and box equal to the asset's: the distant layer
    std::string file, checksum; // set by the reader/writer
    // Bc6h: blocks[k] level k's six faces' BC6H blocks (faces in order, a face's blocks row by
    // row: what KTX2 stores and the GPU upload copies), and `map` holds their decoding (what
    // the GPU samples and the CPU twin reads). Empty for None.
    std::vector<std::vector<std::uint8_t>> blocks;
    // The local layer when the asset has one (faceRes localFaceRes, local = the asset's
    // sphere, alpha in [0, 1]); faceRes 0 otherwise.
    PemMap local;
    std::string localFile, localChecksum; // set by the reader/writer
};

struct PemAsset {
    std::string manifestPath; // where it was read from (errors); empty when cooked
    ProbeInputs inputs;       // what the cooker baked it from ("inputs"; not recorded: empty)
    glm::vec3 centre{0.f};    // world position of the maps' origin (the probe centre)
    std::string skySource; // the sky the bake traced (a path as given; empty: black, or unknown in
                           // a manifest older than "sky_source")
    std::string parameterKind = "viewpoint"; // "viewpoint" | "reflector"
    std::string path = "orbit";              // the walk path the parameter runs along
    int faceRes = 0;
    // The camera image the maps were inferred for (their rows are its pixel centres): drawn at
    // another size, every pixel is off the manifold. 0 x 0: not recorded (older manifests).
    int imageWidth = 0, imageHeight = 0;
    glm::vec3 boxMin{-1.f}, boxMax{1.f}; // probe-local map box
    // Every sample map's geometry: "box" (the map box) or "distance" (the distance cube
    // below, which every sample's map.distance then points to as well). A manifest written
    // before distance geometry existed has no "geometry" field and reads as "box".
    std::string geometry = "box";
    std::shared_ptr<const PemDistanceGeometry> distance; // set iff geometry == "distance"
    std::string distanceFile, distanceChecksum;          // set by the reader
    std::vector<PemSampleMap> samples;                   // parameter strictly increasing
    // The local layer (Hakura §4, "Layered EMs"): what the reflector shows of itself, drawn over
    // the distant layer off the reflector's hull (pem_hull.h). The cooker adds it where reflector
    // rays see their own reflector again. Manifests without "local_layer" have none.
    bool localLayer = false;
    int localFaceRes = 0; // 1 .. 4096 with a local layer
    PemLocalSphere localSphere;
    // MIP levels of every sample's distant map (Hakura §4: inferred together, not filtered
    // copies), 1 .. PemMap::maxLevels(faceRes); each sample's map.levels equals it. Manifests
    // without "mip_levels" hold level 0 alone.
    int mipLevels = 1;
    PemCompression compression = PemCompression::None; // "compression"; absent: None
};

// Most samples a manifest may list (each is a full cube map).
inline constexpr int kMaxPemSamples = 1024;

// Reads and validates a manifest and its images: format, version and flavour, every field's
// type and range, parameters in [0, 1] strictly increasing, each file a plain name inside the
// folder with a matching checksum, each image a float KTX2 cube of exactly N x 6N whose RGB is
// finite in [0, kMaxRadiance]; distance geometry: its parameters, distance.ktx2 a float KTX2 cube
// of exactly M x 6M with a matching checksum whose first channel lies in (0, d_inf]; a local layer:
// every sample's "local" file an RGBA float KTX2 cube of exactly L x 6L with a matching checksum (a
// missing or wrong-sized one names the manifest and "samples[k].local.file"), RGB as the maps',
// alpha in [0, 1]; MIP levels: every sample's "mips" lists one file per level past 0, each exactly
// its level's size (a missing one names the manifest and "samples[k].mips[i].file", a mis-sized one
// its file); compression "bc6h": every sample and MIP file BC6H blocks (a float one names its file
// and "vkFormat"), "compression" in a manifest older than 3.2 refused. Errors name the file and
// the field.
PemAsset readPemProbe(const ProbeManifest& manifest);
PemAsset readPemProbe(const std::string& manifestPath);

} // namespace specula
