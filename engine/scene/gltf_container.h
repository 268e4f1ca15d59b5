#pragma once
// Internal to the glTF loader: the file's bytes and the GLB container around the JSON.
#include <cstddef>
#include <string>
#include <vector>

namespace specula::gltf_internal {

// The whole file, bounded by what tinygltf can address; an empty file is an error.
std::vector<unsigned char> readWholeFile(const std::string& path);

struct GlbLayout {
    std::size_t length = 0; // bytes of the file that belong to the GLB
    const unsigned char* json = nullptr;
    std::size_t jsonSize = 0;
    bool hasBin = false;
    std::size_t binSize = 0;
    std::size_t binChunkOffset = 0; // of the chunk header
};

// Checks the GLB container before tinygltf sees it, so that every structural defect gets a
// precise message (tinygltf's own checks are coarser and miss a chunk header overrun).
// The layout points into `bytes`.
GlbLayout validateGlb(const std::string& file, const std::vector<unsigned char>& bytes);

// A GLB with `json` as its JSON chunk and the original BIN chunk, if any.
std::vector<unsigned char> rebuildGlb(const std::vector<unsigned char>& original,
                                      const GlbLayout& glb, std::string json);

} // namespace specula::gltf_internal
