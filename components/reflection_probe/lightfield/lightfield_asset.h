#pragma once
// A cooked light-field-slab probe (Yu, Yang, McMillan 2005; docs/design.md §5): six slabs around a
// cubic cell of side l, each NUM x NUM cameras of RES x RES pixels with a 90 degree field of
// view looking out along the slab axis.
//
// Atlas layout (one GL_TEXTURE_2D_ARRAY per probe, 6 layers):
//   layer k = slab k in cube-face order +X -X +Y -Y +Z -Z (the slab axis a = k / 2, sign
//   + for even k). Slab axes: b = (a + 1) % 3, c = (a + 2) % 3 (X: y,z; Y: z,x; Z: x,y).
//   Each layer is a (NUM * RES)^2 atlas; camera (i, j) (i along b, j along c) owns the tile
//   of texels [i RES, (i+1) RES) x [j RES, (j+1) RES). Within a tile, texel (x, y) holds the
//   ray with slope (d_b, d_c) / |d_a| = ((x + 0.5) 2 / RES - 1, (y + 0.5) 2 / RES - 1).
//   Camera i sits at s_i = (i / (NUM - 1) - 1/2) 3l on the plane d_a = +-l/2: the outermost
//   cameras lie on the edges of the 3l-wide plane, so every continuous camera index of a ray
//   through the cell is in [0, NUM - 1] and interpolates between two real cameras.
//   Texels are sRGB-encoded 8-bit RGB (GL_SRGB8_ALPHA8) or BC1 blocks of sRGB colour
//   (GL_COMPRESSED_SRGB_S3TC_DXT1_EXT); RES is a multiple of 4 so BC1 blocks never straddle
//   two cameras. Limits: NUM * RES <= 16384 (2D texture side), 6 layers (<= 2048), so the
//   paper's 32 x 128 is a 4096^2 x 6 array: 384 MiB uncompressed, 48 MiB BC1.
// On disk: manifest.json plus one raw file per slab holding exactly the bytes uploaded
// (rows top to bottom: RGB8 texels, or BC1 blocks in block-row order), with checksums.
#include "components/reflection_probe/manifest_fields.h"
#include "engine/image/bc1.h" // slab texels may be BC1 blocks: encodeBC1, decodeBC1

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace specula {

enum class LightFieldCompression { None, BC1 };
const char* toString(LightFieldCompression c);

struct LightFieldSlab {
    // Axial depth (along the slab axis, from the camera plane) of what the cameras see, over
    // the samples whose line passes through the cell (the only ones a reflector in the cell
    // reads). nearDepth/farDepth are the robust range (percentiles, sky = +inf) that sets
    // the focal plane; minDepth/maxDepth the extremes of the hits beyond the plane.
    float nearDepth = 0.f, farDepth = 0.f; // farDepth = +inf when the sky is in range
    float minDepth = 0.f, maxDepth = 0.f;
    float skyFraction = 0.f;        // share of those samples that see the sky
    float intrudingFraction = 0.f;  // share that hit geometry before the camera plane
    float focalDepth = 0.f;         // harmonic mean of near and far (+inf: far is the sky)
    float disparity = 0.f;          // focal-plane disparity, pixels per camera step
    std::vector<std::uint8_t> data; // the atlas layer as uploaded (see the header comment)
    std::string file, checksum;
};

struct LightFieldIntrusion {
    std::string object;
    std::string region; // "cell" or the slab region, e.g. "slab -Y"
    float depth = 0.f;  // how far (metres) the object's bounds reach into that region
};

struct LightFieldAsset {
    glm::vec3 cellCentre{0.f}; // world space
    ProbeInputs inputs;        // what the cooker baked it from ("inputs"; not recorded: empty)
    float cellSize = 1.f;      // l
    int cameras = 8;           // NUM per side
    int res = 64;              // RES
    LightFieldCompression compression = LightFieldCompression::None;
    float depthPercentile = 0.4f; // the robust range's lower/upper percentile
    double bakeSeconds = 0.0;
    std::array<LightFieldSlab, 6> slabs;
    std::vector<LightFieldIntrusion> intrusions;

    int atlasSize() const { return cameras * res; }
    float halfCell() const { return 0.5f * cellSize; }
    // Distance between neighbouring cameras: 3l / (NUM - 1).
    float cameraSpacing() const { return 3.f * cellSize / float(cameras - 1); }
    // Bytes of one slab's atlas layer as stored on disk (RGB8 or BC1).
    std::size_t layerBytes() const;
    std::size_t diskBytes() const { return 6 * layerBytes(); }
    // Texture memory of the atlas array: RGB8 is held as GL_SRGB8_ALPHA8, 4 bytes a texel.
    std::size_t gpuBytes() const {
        const std::size_t n = std::size_t(atlasSize());
        return compression == LightFieldCompression::BC1 ? diskBytes() : 6 * n * n * 4;
    }
};

// Disparity (pixels per camera step) that puts the focal plane at axial depth z: a point at
// depth z moves by spacing / z in slope, i.e. spacing / z * RES / 2 pixels, per camera.
float disparityForDepth(const LightFieldAsset& a, float focalDepth);

// The names of the slabs in layer order: "+X", "-X", "+Y", "-Y", "+Z", "-Z".
const char* slabName(int slab);

// Checks NUM, RES, cell size and compression against the storage limits; throws Error
// naming `source` and the manifest field (cameras, image_res, cell.size); a tool maps the
// field to its flag when source is empty.
void validateLightFieldSize(int cameras, int res, float cellSize, LightFieldCompression c,
                            const std::string& source);

// The figures of one slab against each other (near <= focal <= far, the disparity its focal
// depth gives, disjoint fractions): the reader's check, which the writer
// (writer/lightfield_probe_writer.h) runs before writing. Errors name `manifest` and
// `path` + the field.
void checkLightFieldSlabFigures(const LightFieldAsset& a, const LightFieldSlab& s,
                                const std::string& manifest, const std::string& path);

// Reads and validates a light-field manifest and its slab files: version, every field's type
// and range (cell centre within kMaxCoordinate, integers integral), the atlas and file sizes
// exact for NUM, RES and the compression, each slab's depths consistent (near <= focal <=
// far, disparity from the focal depth), checksums, BC1 blocks decodable. Slab files are read
// once and only when regular files (no FIFO, device or directory). Errors name the file
// and the field.
LightFieldAsset readLightFieldProbe(const std::string& manifestPath);

// readLightFieldProbe on a manifest already parsed (the system reads each manifest once;
// the fuzzer parses text in memory): its path names it in errors and locates the slabs.
LightFieldAsset readLightFieldProbe(const ProbeManifest& manifest);

} // namespace specula
