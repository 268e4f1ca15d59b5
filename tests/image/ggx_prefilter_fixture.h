#pragma once
// The cube maps of the GGX prefilter tests: texel centres and cubes filled from a function.
#include "engine/image/ggx_prefilter.h"
#include "engine/math/cube_face.h"

#include <functional>

#include <glm/geometric.hpp>

namespace specula::test::ggx_prefilter {

inline constexpr double kPi = 3.14159265358979323846;

// The unit direction through the centre of texel (x, y) of an n x n face, straight from the
// repo's face convention.
inline glm::dvec3 texelCentre(int face, int n, int x, int y) {
    const glm::vec3 d =
        glsl::cubeFaceDirection(face, glm::vec2((x + 0.5f) / float(n), (y + 0.5f) / float(n)));
    return glm::normalize(glm::dvec3(d));
}

using Environment = std::function<glm::dvec3(const glm::dvec3&)>;

// A cube whose texels hold the environment at their centres, A = `distance`.
inline CubeFaces makeCube(int n, const Environment& env, float distance = 5.f) {
    CubeFaces faces;
    for (int f = 0; f < 6; ++f) {
        faces[f] = Image(n, n, 4);
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const glm::dvec3 c = env(texelCentre(f, n, x, y));
                float* p = faces[f].at(x, y);
                p[0] = float(c.x);
                p[1] = float(c.y);
                p[2] = float(c.z);
                p[3] = distance;
            }
    }
    return faces;
}

} // namespace specula::test::ggx_prefilter
