#pragma once
// The CPU twin of the parameterized-environment-map lookup (shaders/pem_lookup.glsl.h): the
// same code compiled as C++, either reading a map (radiance) or reporting which texels it
// reads and with what weight (weights). The cooker builds its rendering matrix from
// `weights`, so the map it infers is the best match as this very lookup applies it.
#include <glm/vec3.hpp>

#include <utility>
#include <vector>

namespace specula {

// One map of box geometry: six N x N faces in OpenGL order (+X -X +Y -Y +Z -Z, OpenGL face
// orientation), linear RGB, texel (face, column i, row j) at face*N*N + j*N + i. The box is
// probe-local and holds the reflector; the map's centre is the probe origin.
struct PemMap {
    int faceRes = 0;
    glm::vec3 boxMin{-1.f}, boxMax{1.f};
    std::vector<glm::vec3> texels; // 6 * faceRes * faceRes

    static int texelCount(int faceRes) { return 6 * faceRes * faceRes; }
};

// (texel index, weight) pairs of one lookup; each texel at most once, no zero weights.
using PemWeights = std::vector<std::pair<int, float>>;

class PemLookupCpu {
public:
    explicit PemLookupCpu(const PemMap& map) : map_(&map) {}

    // x: probe-local reflector point (inside the box), l: unit reflected direction.
    glm::vec3 radiance(glm::vec3 x, glm::vec3 l) const;

    // The texels radiance(x, l) reads and their weights, so that radiance(x, l) equals
    // sum(weight * texel) up to float rounding. Needs only the map's geometry (faceRes,
    // box), not its texels. `out` is cleared first.
    void weights(glm::vec3 x, glm::vec3 l, PemWeights& out) const;

private:
    const PemMap* map_;
};

} // namespace specula
