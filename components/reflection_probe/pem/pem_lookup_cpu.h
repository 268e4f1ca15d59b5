#pragma once
// The CPU twin of the parameterized-environment-map lookups (shaders/pem_lookup.glsl.h for
// box geometry, shaders/pem_distance_lookup.glsl.h for distance geometry): the same code
// compiled as C++, either reading a map (radiance) or reporting which texels it
// reads and with what weight (weights). The cooker builds its rendering matrix from
// `weights`, so the map it infers is the best match as this very lookup applies it.
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace specula {

// Distance geometry of a map (shaders/pem_distance_lookup.glsl.h): the environment's
// distance from the map centre through every texel centre of its own cube (mirrors
// excluded), dInf where nothing is hit, and the secant search's parameters. Shared by every
// sample map of an asset: it is the scene's, not the parameter's.
struct PemDistanceGeometry {
    int faceRes = 0;              // texels along a face edge, 1 .. 4096
    std::vector<float> distances; // 6 * faceRes^2, texel order as PemMap's; in (0, dInf]
    float dInf = 0.f;             // sentinel of texels that see nothing; > 2 * every distance
    float range = 0.f;            // D: every hit lies within (x, x + 2D l); <= dInf / 2
    float tolerance = 0.f;        // d_e: the search stops when |stored - |l|| < d_e
    int maxSteps = 0;             // fetches of the search, 1 .. 40

    bool operator==(const PemDistanceGeometry&) const = default;
};

// The local layer's geometry (shaders/pem_local_lookup.glsl.h): a sphere fitted to the
// reflector, probe-local.
struct PemLocalSphere {
    glm::vec3 centre{0.f};
    float radius = 1.f; // > 0

    bool operator==(const PemLocalSphere&) const = default;
};

// One map: six N x N faces in OpenGL order (+X -X +Y -Y +Z -Z, OpenGL face orientation),
// linear RGB, texel (face, column i, row j) at face*N*N + j*N + i. The box is probe-local and
// holds the reflector; the map's centre is the probe origin. Geometry: the box when
// `distance` is null, else the distance cube (the box then only bounds the reflector).
// MIP levels (distant maps): level k has faces of max(N >> k, 1) texels, as GL halves a
// texture array's levels, and its texels follow level k - 1's (levelOffset).
struct PemMap {
    int faceRes = 0;
    glm::vec3 boxMin{-1.f}, boxMax{1.f};
    std::vector<glm::vec3> texels; // texelCount(faceRes, levels)
    std::shared_ptr<const PemDistanceGeometry> distance;
    // A local layer (set: the sphere lookup, box and distance unused): texels hold
    // premultiplied RGB and `alpha` the coverage, one per texel. Unset: `alpha` is empty.
    std::optional<PemLocalSphere> local{};
    std::vector<float> alpha{};
    int levels = 1; // 1 .. maxLevels(faceRes); a local map has one

    static int texelCount(int faceRes) { return 6 * faceRes * faceRes; }
    static int levelRes(int faceRes, int level) { return std::max(faceRes >> level, 1); }
    // Down to 1 x 1 faces: floor(log2 N) + 1.
    static int maxLevels(int faceRes) {
        int k = 1;
        while ((faceRes >> k) > 0)
            ++k;
        return k;
    }
    static int levelOffset(int faceRes, int level) {
        int offset = 0;
        for (int k = 0; k < level; ++k)
            offset += texelCount(levelRes(faceRes, k));
        return offset;
    }
    static int texelCount(int faceRes, int levels) { return levelOffset(faceRes, levels); }
};

// A pixel's footprint, as the shader differentiates it (dFdxFine, dFdyFine along the
// window's x and y): of the probe-local reflector point x and of the unit reflected direction
// l. It picks the MIP level of a multi-level map (shaders/pem_lod.glsl.h); single-level maps
// ignore it. Zero: level 0.
struct PemFootprint {
    glm::vec3 dxdX{0.f}, dxdY{0.f}, dldX{0.f}, dldY{0.f};
    // Finite: the level of detail itself, the derivatives ignored (what the shader's OUTPUT 4
    // reads back, so a test can hold the lookup apart from the derivatives).
    float lod = std::numeric_limits<float>::quiet_NaN();
};

// Throws Error(file, field) unless `g` is usable: "distance.face_res", "distance.d_inf",
// "distance.range", "distance.tolerance", "distance.max_steps" name `file`; a distance
// outside (0, dInf] (or a wrong count) names `distanceFile` and "distance".
void checkPemDistanceGeometry(const PemDistanceGeometry& g, const std::string& file,
                              const std::string& distanceFile);

// (texel index, weight) pairs of one lookup; each texel at most once, no zero weights.
using PemWeights = std::vector<std::pair<int, float>>;

class PemLookupCpu {
public:
    explicit PemLookupCpu(const PemMap& map) : map_(&map) {}

    // x: probe-local reflector point (inside the box), l: unit reflected direction, f: the
    // pixel's footprint (multi-level maps only). A local map gives its premultiplied RGB.
    glm::vec3 radiance(glm::vec3 x, glm::vec3 l, const PemFootprint& f = {}) const;
    // A local map's premultiplied RGB and coverage alpha (the shader's pemLocalRadiance).
    glm::vec4 localRadiance(glm::vec3 x, glm::vec3 l) const;

    // The texels radiance(x, l) reads and their weights, so that radiance(x, l) equals
    // sum(weight * texel) up to float rounding. Needs only the map's geometry (faceRes,
    // box, distance), not its texels. `out` is cleared first.
    // Texel indices of a multi-level map run over every level (PemMap::levelOffset).
    void weights(glm::vec3 x, glm::vec3 l, PemWeights& out, const PemFootprint& f = {}) const;
    // The weights of a local map are those of its alpha too: one RGBA bilinear.

    // The level of detail a multi-level map is read at, before clamping to its levels (the
    // shader's pemFootprintLod); log2 of the footprint in level-0 texels.
    float lod(glm::vec3 x, glm::vec3 l, const PemFootprint& f) const;

    // Texture fetches radiance(x, l) makes, as the bench counts them for every method: one per
    // bilinear read of the map (its four texelFetch calls are one filtered fetch elsewhere),
    // one per distance-cube read of the search.
    int textureFetches(glm::vec3 x, glm::vec3 l) const;

private:
    const PemMap* map_;
};

} // namespace specula
