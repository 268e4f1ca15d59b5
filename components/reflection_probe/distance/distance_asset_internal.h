#pragma once
// What the distance probe's reader and writer share between distance_probe_asset.cpp (the
// manifest, the layers and the sky) and distance_glossy_asset.cpp (the glossy levels). Not
// part of the component's API: only those two files include it.
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

// --- the glossy levels (distance_glossy_asset.cpp) -------------------------------------------

// The glossy levels against the composite: each level's size, every texel (as a layer's)
// and its distances. `files[k]` names glossy level k + 1's image.
void checkGlossy(const DistanceProbeAsset& a, const std::string& manifest,
                 const std::vector<std::string>& files);

// Where the writer puts each glossy level's image in `dir`: [k] is level k + 1's.
std::vector<std::string> glossyFilePaths(const DistanceProbeAsset& asset, const std::string& dir);

// Writes each glossy level's image into `tmp` (throwIfCancelled(dir) before each) and
// returns the manifest's "glossy" member. Only for an asset with glossy levels.
nlohmann::json writeGlossyLevels(const DistanceProbeAsset& asset, const std::filesystem::path& tmp,
                                 const std::string& dir);

// The manifest's "glossy" member: each level's file (checksum, a float KTX2 cube of the level's
// size) into a.glossyLevels, its path into `files`; its content is checked with the layers'
// (checkGlossy).
void readGlossyLevels(const ManifestFields& r, const nlohmann::json& glossy,
                      const std::filesystem::path& dir, DistanceProbeAsset& a,
                      std::vector<std::string>& files);

} // namespace specula::distance_asset
