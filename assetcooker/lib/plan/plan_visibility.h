#pragma once
// What the probe centre sees of each environment object on its own (the others ignored), on
// a low-resolution cube: the effect plan's input. One Embree scene holds the whole
// environment; each object traces only the texels inside the cone of its bounding sphere and
// accepts hits on its own meshes. The work is O(objects x texels each covers) rays plus one
// BVH build, where a cube baked per object was O(objects x whole cube) and a BVH per object.
#include "assetcooker/lib/scene/scene_markup.h"
#include "engine/ecs/registry.h"

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace specula {

// The texels of an n x n cube map, indexed (face * n + y) * n + x.
struct CubeTexels {
    int n = 0;
    std::vector<glm::vec3> dirs;    // unit direction through each texel's centre
    std::vector<float> solidAngles; // steradians

    explicit CubeTexels(int faceRes);
    std::size_t size() const { return dirs.size(); }
};

struct ObjectView {
    float solidAngle = 0.f;             // steradians the object covers (0: it hides in texels)
    float nearest = 0.f, average = 0.f; // metres; average weighted by solid angle
    std::vector<std::uint32_t> texels;  // the texels whose centre ray meets it
};

// One view per markup object, in markup order.
std::vector<ObjectView> viewObjectsFromCentre(ecs::Registry& registry, const SceneMarkup& markup,
                                              glm::vec3 centre, const CubeTexels& cube);

// Texels whose centre direction lies within `halfAngle` of the unit `axis` (a bounding cone;
// half a texel wider so a texel the cone clips still counts).
std::vector<std::uint32_t> texelsInCone(const CubeTexels& cube, glm::vec3 axis, float halfAngle);

// `texels` as a mask grown by `grow` texels within each face (a square window, clipped to
// the face): a conservative stand-in for the parallax a moving reflector adds. Separable, so
// O(texels) whatever the growth.
std::vector<char> grownMask(const std::vector<std::uint32_t>& texels, int n, int grow);

} // namespace specula
