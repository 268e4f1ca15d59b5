#pragma once
// An orthonormal frame (t, b, n) about a unit normal, without the singularity of a fixed
// helper axis (Duff et al. 2017, "Building an Orthonormal Basis, Revisited"). The ground
// truth samples lobes in it and the plan draws reflected rays in it.
#include <cmath>

#include <glm/vec3.hpp>

namespace specula {

struct OrthonormalFrame {
    glm::vec3 t, b; // tangent and bitangent; (t, b, n) is right-handed
};

inline OrthonormalFrame orthonormalFrame(glm::vec3 n) {
    const float sign = std::copysign(1.f, n.z);
    const float a = -1.f / (sign + n.z);
    const float c = n.x * n.y * a;
    return {glm::vec3(1.f + sign * n.x * n.x * a, sign * c, -sign * n.x),
            glm::vec3(c, sign + n.y * n.y * a, -n.y)};
}

} // namespace specula
