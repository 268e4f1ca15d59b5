#pragma once
// Internal to the glTF loader: the first animation's node channels (translation, rotation,
// scale) as NodeAnimation components, every index, accessor and key checked.
#include "engine/scene/animation.h"
#include "engine/scene/gltf_context.h"

#include <map>

namespace specula::gltf_internal {

// By glTF node index. Only animations[0] is read (a file's animations are alternatives: a
// walk, a run; the others are reported in the warnings), and of it every channel whose path
// is translation, rotation or scale ("weights" morph targets are skipped with a warning).
// Throws Error naming the field: a sampler, node or accessor index out of range, an
// interpolation other than LINEAR, STEP or CUBICSPLINE, key times not finite and strictly
// increasing, a value count unlike the keys' (three per key for CUBICSPLINE), a value not
// finite, a zero rotation, two channels driving one node's same path.
std::map<int, NodeAnimation> readNodeAnimations(Context& ctx);

} // namespace specula::gltf_internal
