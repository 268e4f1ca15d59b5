#pragma once
// tinygltf, configured identically for its implementation unit and its users: a mismatch
// in these macros would change the layout of tinygltf's classes between translation units.
//
// Image decoding and Draco decoding are deliberately NOT left to tinygltf:
// - tinygltf 2.7 hands image callbacks a pointer computed from an unchecked bufferView
//   range, so images are kept encoded (as_is) and decoded by the loader after it has
//   validated the range itself;
// - tinygltf 2.7's KHR_draco_mesh_compression path indexes bufferViews and accessors
//   without bounds checks, dereferences missing attributes and ignores decode failures,
//   so the loader decodes Draco payloads itself with libdraco (see gltf_draco.cpp).
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wall"
#pragma GCC diagnostic ignored "-Wextra"
#pragma GCC diagnostic ignored "-Wpedantic"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wtype-limits"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#endif
#include <tiny_gltf.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
