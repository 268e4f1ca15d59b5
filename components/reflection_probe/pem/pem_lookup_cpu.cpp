#include "pem_lookup_cpu.h"

#include "engine/core/glsl_host.h"
#include "engine/math/cube_face.h"

#include <array>
#include <cassert>
#include <cstddef>

namespace specula {
namespace glsl {

// Reads the map, as the GPU's texelFetch will.
struct PemTexelRead {
    const PemMap* map = nullptr;

    vec3 fetchTexel(int face, int i, int j) const {
        const int n = map->faceRes;
        return map->texels[std::size_t((face * n + j) * n + i)];
    }
};

// The shared lookup is included inside a struct so its fetchTexel calls bind to the member.
struct PemReadTwin : PemTexelRead {
#include "components/reflection_probe/pem/shaders/pem_lookup.glsl.h"
};
#undef SPECULA_PEM_LOOKUP_GLSL_H

// Measures the lookup's weights by linearity, as Hakura et al. build the rendering matrix
// from test renderings that isolate each texel: on pass p, fetch number k of the lookup reads
// a texel that is 1 in channel k - 3p when 3p <= k < 3p + 3 and black otherwise, so the
// result's three channels are the weights the lookup gave fetches 3p .. 3p+2, whatever
// arithmetic it used to apply them. Texel indices are recorded on the way; they depend on
// the ray only, so every pass fetches the same texels in the same order.
struct PemTexelProbe {
    static constexpr int kMaxFetches = 16; // 4 now; trilinear MIP lookups will need 8
    int faceRes = 0;
    int pass = 0;
    int fetches = 0;
    std::array<int, kMaxFetches> index{};

    vec3 fetchTexel(int face, int i, int j) {
        const int k = fetches++;
        assert(k < kMaxFetches);
        if (pass == 0) index[std::size_t(k)] = (face * faceRes + j) * faceRes + i;
        vec3 unit(0.0f);
        if (k / 3 == pass) unit[k % 3] = 1.0f;
        return unit;
    }
};

struct PemProbeTwin : PemTexelProbe {
#include "components/reflection_probe/pem/shaders/pem_lookup.glsl.h"
};

} // namespace glsl

glm::vec3 PemLookupCpu::radiance(glm::vec3 x, glm::vec3 l) const {
    glsl::PemReadTwin twin;
    twin.map = map_;
    return twin.pemRadiance(x, l, map_->boxMin, map_->boxMax, map_->faceRes);
}

void PemLookupCpu::weights(glm::vec3 x, glm::vec3 l, PemWeights& out) const {
    out.clear();
    glsl::PemProbeTwin twin;
    twin.faceRes = map_->faceRes;
    int fetches = 0;
    do {
        twin.fetches = 0;
        const glm::vec3 w = twin.pemRadiance(x, l, map_->boxMin, map_->boxMax, map_->faceRes);
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

} // namespace specula
