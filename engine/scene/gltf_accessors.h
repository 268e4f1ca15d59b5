#pragma once
// Internal to the glTF loader: bufferView ranges and accessors, every index and byte range
// checked against the model before it is read.
#include "engine/scene/gltf_context.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace specula::gltf_internal {

struct Span {
    const unsigned char* data = nullptr;
    std::size_t stride = 0;
};

// `count` elements of `elemSize` bytes starting `offset` bytes into bufferView `view`,
// `stride` apart (0: tightly packed, or the view's byteStride when it has one). `field`
// names the accessor (or whatever reads the view) in errors.
Span viewRange(const Context& ctx, int view, std::size_t offset, std::size_t count,
               std::size_t elemSize, bool useViewStride, const std::string& field);

// The whole of bufferView `view` as one blob (an image, a Draco payload); `field` holds the
// view's index in its member "bufferView".
struct Bytes {
    const unsigned char* data = nullptr;
    std::size_t size = 0;
};
Bytes viewBytes(const Context& ctx, int view, const std::string& field);

// Accessor `index` read as VEC3 / VEC2 floats (normalised integers mapped as glTF says),
// sparse substitution included; `from` names the field that refers to it.
std::vector<glm::vec3> readVec3(const Context& ctx, int index, const std::string& from);
std::vector<glm::vec2> readVec2(const Context& ctx, int index, const std::string& from);

// Accessor `index` as `comps` floats per element (SCALAR, VEC3 or VEC4; normalised integers
// mapped as glTF says), flattened: animation keys and their values.
std::vector<float> readFloats(const Context& ctx, int index, int comps, const std::string& from);

// Accessor `index` as SCALAR unsigned integers (triangle indices).
std::vector<std::uint32_t> readIndices(const Context& ctx, int index, const std::string& from);

} // namespace specula::gltf_internal
