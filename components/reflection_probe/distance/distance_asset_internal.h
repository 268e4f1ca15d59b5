#pragma once
// What the distance probe's reader and writer share between distance_probe_asset.cpp (the
// manifest, the layers and the sky), distance_asset_checks.cpp (the content checks),
// distance_glossy_asset.cpp (the glossy levels) and distance_compressed_asset.cpp (a
// compressed composite), and the writer (writer/distance_probe_writer.cpp). Not part of the
// component's API: only those files include it.
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "components/reflection_probe/manifest_fields.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace specula::distance_asset {

// --- shared with the layers (distance_probe_asset.cpp) ---------------------------------------

// Largest file a probe layer of face resolution n can be: an N x 6N float RGBA KTX2 is 96 N^2
// bytes of pixels; the rest (header, offset tables, chunk headers) is far below the margin.
std::uint64_t maxLayerFileBytes(int n);

// Six faces as the N x 6N image a layer file holds, and back.
Image stackFaces(const std::array<Image, 6>& faces);
std::array<Image, 6> splitFaces(const Image& stacked);

// "face +X texel (x, y)"
std::string texelName(int face, int x, int y);

// `v` as printf's %g writes it.
std::string shortNumber(double v);

// Solid angle of every texel of an N x N face, row-major (the same for all six faces):
// computed once per probe, so measuring a layer is one pass over its texels.
std::vector<float> faceSolidAngles(int n);

// Measures a layer and checks every texel (measureDistanceLayer with the solid angles given).
DistanceLayerContent scanLayer(const std::array<Image, 6>& faces, float dInf,
                               const std::vector<float>& solidAngles, const std::string& file);

// --- the content checks (distance_asset_checks.cpp) ------------------------------------------

// Whether RGB are finite radiances in [0, kMaxRadiance] (false for NaN).
bool radianceOk(const float* rgb);
// Throws Error(file, "radiance", ...) for the first RGB channel that is not, naming `where`.
void refuseRadiance(const float* rgb, const std::string& file, const std::string& where);

// Everything the reader checks of the images' content, the writer too before writing, so a
// bake never writes a probe its own reader would refuse: every texel, each layer's figures
// against its image, layer 0 the nearest of the object layers, the glossy levels, the sky.
// `files[i]` names layer i's image, `glossyFiles[k]` glossy level k + 1's.
void checkContent(const DistanceProbeAsset& a, const std::string& manifest,
                  const std::vector<std::string>& files,
                  const std::vector<std::string>& glossyFiles, const std::string& skyFile);

// --- the glossy levels (distance_glossy_asset.cpp) -------------------------------------------

// The glossy levels against the composite: each level's size, every texel (as a layer's)
// and its distances. `files[k]` names glossy level k + 1's image.
void checkGlossy(const DistanceProbeAsset& a, const std::string& manifest,
                 const std::vector<std::string>& files);

// The manifest's "glossy" member: each level's file (checksum, a float KTX2 cube of the level's
// size) into a.glossyLevels, its path into `files`; its content is checked with the layers'
// (checkGlossy).
void readGlossyLevels(const ManifestFields& r, const nlohmann::json& glossy,
                      const std::filesystem::path& dir, DistanceProbeAsset& a,
                      std::vector<std::string>& files);

// --- a compressed composite (distance_compressed_asset.cpp) ----------------------------------

// That a Bc6h asset's blocks decode to exactly its composite's radiance (and its glossy
// levels'), and its distances are half floats when it says so: what the writer checks before
// writing (errors name `file`, the composite's, or glossyFiles[k], glossy level k + 1's).
void checkCompressedComposite(const DistanceProbeAsset& a, const std::string& file,
                              const std::vector<std::string>& glossyFiles);

// Reads a Bc6h composite: `radianceFile` (already checksummed, a BC6H cube of face_res) and
// the layer's "distance" file (path + "distance."); sets a's compression members and returns
// the faces as a layer holds them (decoded radiance, distance in A).
std::array<Image, 6> readCompressedComposite(const ManifestFields& r, const nlohmann::json& layer,
                                             const std::string& path,
                                             const std::filesystem::path& dir,
                                             const std::string& radianceFile,
                                             DistanceProbeAsset& a);

} // namespace specula::distance_asset
