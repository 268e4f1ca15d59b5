#include "pem_lookup_cpu.h"

#include "engine/core/error.h"
#include "engine/core/glsl_host.h"
#include "engine/math/cube_face.h"

#include <array>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <type_traits>

namespace specula {
namespace glsl {
// At namespace scope once, so the lookups included in the structs below share the types.
#include "components/reflection_probe/distance/shaders/distance_lookup_types.glsl.h"

// The twins always compile the MIP path: a single-level map clamps the lod to 0, which
// reads level 0 alone through the same bilinear the shader's PEM_MIP 0 variant runs.
#define PEM_MIP 1

// The map's texel index of (level, face, i, j), levels stacked as PemMap keeps them.
int pemTexelIndex(const PemMap& m, int level, int face, int i, int j) {
    const int n = PemMap::levelRes(m.faceRes, level);
    return PemMap::levelOffset(m.faceRes, level) + (face * n + j) * n + i;
}

// What the MIP hooks of pem_lookup.glsl.h read: the lod the pixel's footprint gave.
struct PemLevelOfDetail {
    float lookupLod = 0.0f;
    int levels = 1;
    float pemLookupLod() const { return lookupLod; }
    int pemMapLevels() const { return levels; }
};

// Reads the map, as the GPU's texelFetch will.
struct PemTexelRead : PemLevelOfDetail {
    const PemMap* map = nullptr;

    vec3 fetchTexel(int level, int face, int i, int j) const {
        return map->texels[std::size_t(pemTexelIndex(*map, level, face, i, j))];
    }
};

// Measures the lookup's weights by linearity, as Hakura et al. build the rendering matrix
// from test renderings that isolate each texel: on pass p, fetch number k of the lookup reads
// a texel that is 1 in channel k - 3p when 3p <= k < 3p + 3 and black otherwise, so the
// result's three channels are the weights the lookup gave fetches 3p .. 3p+2, whatever
// arithmetic it used to apply them. Texel indices are recorded on the way; they depend on
// the ray only (the distance cube is geometry, not a texel), so every pass fetches the same
// texels in the same order.
struct PemTexelProbe : PemLevelOfDetail {
    static constexpr int kMaxFetches = 16; // 4 bilinear, 8 trilinear
    const PemMap* map = nullptr;
    int pass = 0;
    int fetches = 0;
    std::array<int, kMaxFetches> index{};

    vec3 fetchTexel(int level, int face, int i, int j) {
        const int k = fetches++;
        assert(k < kMaxFetches);
        if (pass == 0) index[std::size_t(k)] = pemTexelIndex(*map, level, face, i, j);
        vec3 unit(0.0f);
        if (k / 3 == pass) unit[k % 3] = 1.0f;
        return unit;
    }
};

// What the distance geometry's lookup reads besides the map: the distance cube (nearest).
struct PemDistanceRead {
    const PemDistanceGeometry* geometry = nullptr;
    int mapFaceRes = 0;
    mutable int distanceReads = 0; // texture fetches of the distance cube

    float fetchDistanceTexel(int face, int i, int j) const {
        ++distanceReads;
        const int n = geometry->faceRes;
        return geometry->distances[std::size_t((face * n + j) * n + i)];
    }
    int pemMapFaceRes() const { return mapFaceRes; }
    int pemDistanceFaceRes() const { return geometry->faceRes; }
};

// The shared lookups are included inside structs so their fetch calls bind to the members;
// each struct gets its own copy of the taps (pem_taps.glsl.h), hence the #undef of its guard.
struct PemReadTwin : PemTexelRead {
#include "components/reflection_probe/pem/shaders/pem_lookup.glsl.h"
};
#undef SPECULA_PEM_LOOKUP_GLSL_H
#undef SPECULA_PEM_TAPS_GLSL_H

struct PemProbeTwin : PemTexelProbe {
#include "components/reflection_probe/pem/shaders/pem_lookup.glsl.h"
};
#undef SPECULA_PEM_LOOKUP_GLSL_H
#undef SPECULA_PEM_TAPS_GLSL_H

// The level of detail: the footprint through the box geometry (pem_lod.glsl.h needs
// pemBoxExit, hence the box lookup beside it; its fetches are never called).
struct PemLodTwin : PemTexelRead {
#include "components/reflection_probe/pem/shaders/pem_lod.glsl.h"
#include "components/reflection_probe/pem/shaders/pem_lookup.glsl.h"
};
#undef SPECULA_PEM_LOOKUP_GLSL_H
#undef SPECULA_PEM_TAPS_GLSL_H

// The local layer: RGBA texels, premultiplied RGB and alpha.
struct PemLocalReadTwin : PemTexelRead {
    vec4 fetchLocalTexel(int face, int i, int j) const {
        const std::size_t t = std::size_t((face * map->faceRes + j) * map->faceRes + i);
        return vec4(map->texels[t], map->alpha[t]);
    }
#include "components/reflection_probe/pem/shaders/pem_local_lookup.glsl.h"
};
#undef SPECULA_PEM_LOCAL_LOOKUP_GLSL_H
#undef SPECULA_PEM_TAPS_GLSL_H

// Alpha is filtered with the RGB weights, so measuring RGB's is enough.
struct PemLocalProbeTwin : PemTexelProbe {
    vec4 fetchLocalTexel(int face, int i, int j) { return vec4(fetchTexel(0, face, i, j), 0.0f); }
#include "components/reflection_probe/pem/shaders/pem_local_lookup.glsl.h"
};
#undef SPECULA_PEM_TAPS_GLSL_H

// The distance hooks take the distance lookup's `layer` argument, which a single-layer
// lookup does not need: GLSL does not mind, C++ warns.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
struct PemDistanceReadTwin : PemTexelRead, PemDistanceRead {
#include "components/reflection_probe/pem/shaders/pem_distance_lookup.glsl.h"
#include "components/reflection_probe/pem/shaders/pem_lookup.glsl.h"
};
#undef SPECULA_PEM_LOOKUP_GLSL_H
#undef SPECULA_PEM_TAPS_GLSL_H
#undef SPECULA_PEM_DISTANCE_LOOKUP_GLSL_H
#undef SPECULA_DISTANCE_LOOKUP_GLSL_H

struct PemDistanceProbeTwin : PemTexelProbe, PemDistanceRead {
#include "components/reflection_probe/pem/shaders/pem_distance_lookup.glsl.h"
#include "components/reflection_probe/pem/shaders/pem_lookup.glsl.h"
};
#pragma GCC diagnostic pop
#undef PEM_MIP

} // namespace glsl

namespace {

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

// The level of detail for footprint f on map m (pem_lod.glsl.h; 0 for a single level).
float levelOfDetail(const PemMap& m, glm::vec3 x, glm::vec3 l, const PemFootprint& f) {
    if (m.levels <= 1) return 0.f;
    if (std::isfinite(f.lod)) return f.lod;
    glsl::PemLodTwin twin;
    return twin.pemFootprintLod(x, l, f.dxdX, f.dxdY, f.dldX, f.dldY, m.boxMin, m.boxMax,
                                m.faceRes);
}

template <typename Twin>
glm::vec3 lookup(Twin& twin, const PemMap& m, glm::vec3 x, glm::vec3 l, const PemFootprint& f) {
    twin.levels = m.levels;
    twin.lookupLod = levelOfDetail(m, x, l, f);
    if constexpr (std::is_same_v<Twin, glsl::PemLocalReadTwin> ||
                  std::is_same_v<Twin, glsl::PemLocalProbeTwin>) {
        return glm::vec3(twin.pemLocalRadiance(x, l, m.local->centre, m.local->radius, m.faceRes));
    } else if constexpr (std::is_base_of_v<glsl::PemDistanceRead, Twin>) {
        const PemDistanceGeometry& g = *m.distance;
        twin.geometry = &g;
        twin.mapFaceRes = m.faceRes;
        return twin.pemDistanceRadiance(
            x, l, twin.pemDistanceParams(g.dInf, g.range, g.tolerance, g.maxSteps));
    } else {
        return twin.pemRadiance(x, l, m.boxMin, m.boxMax, m.faceRes);
    }
}

// Runs the recording twin pass by pass (PemTexelProbe) and gathers its weights.
template <typename Twin>
void measureWeights(Twin& twin, const PemMap& m, glm::vec3 x, glm::vec3 l, const PemFootprint& f,
                    PemWeights& out) {
    out.clear();
    twin.map = &m;
    int fetches = 0;
    do {
        twin.fetches = 0;
        const glm::vec3 w = lookup(twin, m, x, l, f);
        assert(twin.pass == 0 || twin.fetches == fetches);
        fetches = twin.fetches;
        for (int c = 0; c < 3 && 3 * twin.pass + c < fetches; ++c) {
            const int texel = twin.index[std::size_t(3 * twin.pass + c)];
            const float weight = w[c];
            if (weight == 0.f) continue; // e.g. a ray exactly on a texel centre row
            // Clamping at a face edge fetches one texel twice: one entry, weights summed.
            auto it = out.begin();
            while (it != out.end() && it->first != texel)
                ++it;
            if (it == out.end())
                out.emplace_back(texel, weight);
            else
                it->second += weight;
        }
    } while (3 * ++twin.pass < fetches);
}

} // namespace

void checkPemDistanceGeometry(const PemDistanceGeometry& g, const std::string& file,
                              const std::string& distanceFile) {
    if (g.faceRes < 1 || g.faceRes > 4096)
        throw Error(file, "distance.face_res",
                    "expected an integer in [1, 4096], got " + std::to_string(g.faceRes));
    if (!(g.dInf > 0.f) || !std::isfinite(g.dInf))
        throw Error(file, "distance.d_inf", "expected a finite d_inf > 0, got " + number(g.dInf));
    // Past d_inf / 2 the search would treat its own points as seeing nothing.
    if (!(g.range > 0.f && g.range <= 0.5f * g.dInf))
        throw Error(file, "distance.range",
                    "expected D in (0, d_inf / 2 = " + number(0.5 * g.dInf) + "], got " +
                        number(g.range));
    if (!(g.tolerance > 0.f && g.tolerance < g.range))
        throw Error(file, "distance.tolerance",
                    "expected d_e in (0, D), got " + number(g.tolerance));
    if (g.maxSteps < 1 || g.maxSteps > 40)
        throw Error(file, "distance.max_steps",
                    "expected an integer in [1, 40], got " + std::to_string(g.maxSteps));
    const std::size_t count = std::size_t(PemMap::texelCount(g.faceRes));
    if (g.distances.size() != count)
        throw Error(distanceFile, "distance",
                    "expected " + std::to_string(count) + " distances, got " +
                        std::to_string(g.distances.size()));
    for (std::size_t t = 0; t < count; ++t) {
        const float d = g.distances[t];
        if (d > 0.f && d <= g.dInf) continue; // false for NaN too
        const int n = g.faceRes;
        throw Error(distanceFile, "distance",
                    "face " + std::to_string(int(t) / (n * n)) + " texel (" +
                        std::to_string(int(t) % n) + ", " + std::to_string(int(t) / n % n) +
                        ") holds " + number(d) +
                        "; expected a distance in (0, d_inf = " + number(g.dInf) + "]");
    }
}

glm::vec3 PemLookupCpu::radiance(glm::vec3 x, glm::vec3 l, const PemFootprint& f) const {
    if (map_->local) return glm::vec3(localRadiance(x, l));
    if (map_->distance) {
        glsl::PemDistanceReadTwin twin;
        twin.map = map_;
        return lookup(twin, *map_, x, l, f);
    }
    glsl::PemReadTwin twin;
    twin.map = map_;
    return lookup(twin, *map_, x, l, f);
}

glm::vec4 PemLookupCpu::localRadiance(glm::vec3 x, glm::vec3 l) const {
    assert(map_->local && map_->alpha.size() == map_->texels.size());
    glsl::PemLocalReadTwin twin;
    twin.map = map_;
    return twin.pemLocalRadiance(x, l, map_->local->centre, map_->local->radius, map_->faceRes);
}

float PemLookupCpu::lod(glm::vec3 x, glm::vec3 l, const PemFootprint& f) const {
    glsl::PemLodTwin twin;
    return twin.pemFootprintLod(x, l, f.dxdX, f.dxdY, f.dldX, f.dldY, map_->boxMin, map_->boxMax,
                                map_->faceRes);
}

int PemLookupCpu::textureFetches(glm::vec3 x, glm::vec3 l) const {
    if (map_->local || !map_->distance) return 1;
    glsl::PemDistanceReadTwin twin;
    twin.map = map_;
    lookup(twin, *map_, x, l, PemFootprint{});
    return twin.distanceReads + 1; // the search's distance reads, then the map's filtered read
}

void PemLookupCpu::weights(glm::vec3 x, glm::vec3 l, PemWeights& out, const PemFootprint& f) const {
    if (map_->local) {
        glsl::PemLocalProbeTwin twin;
        measureWeights(twin, *map_, x, l, f, out);
    } else if (map_->distance) {
        glsl::PemDistanceProbeTwin twin;
        measureWeights(twin, *map_, x, l, f, out);
    } else {
        glsl::PemProbeTwin twin;
        measureWeights(twin, *map_, x, l, f, out);
    }
}

} // namespace specula
