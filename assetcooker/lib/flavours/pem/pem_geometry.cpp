#include "assetcooker/lib/flavours/pem/pem_geometry.h"

#include "components/reflection_probe/distance/distance_lookup_config.h" // bisectionSteps
#include "engine/core/error.h"
#include "engine/core/glsl_host.h"
#include "engine/math/cube_face.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace specula {

PemDistanceGeometry bakePemDistanceGeometry(const GroundTruthTracer& tracer, glm::vec3 centre,
                                            int faceRes, float dInf,
                                            std::vector<glm::vec3>* capturedRadiance) {
    if (faceRes < 1 || faceRes > 4096)
        throw Error("", "face_res", "expected 1 to 4096, got " + std::to_string(faceRes));
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(centre[i])) throw Error("", "centre", "expected finite numbers");
    if (!(dInf > 0.f) || !std::isfinite(dInf))
        throw Error("", "d_inf", "expected a finite d_inf > 0");

    const int n = faceRes;
    PemDistanceGeometry g;
    g.faceRes = n;
    g.dInf = dInf;
    g.distances.assign(std::size_t(PemMap::texelCount(n)), dInf);
    std::vector<glm::vec3> radiance(g.distances.size(), glm::vec3(0.f));
    // One task per texel row of a face (6N rows): each texel is written by exactly one.
    tbb::parallel_for(tbb::blocked_range<int>(0, 6 * n), [&](const tbb::blocked_range<int>& r) {
        for (int row = r.begin(); row < r.end(); ++row) {
            const int face = row / n, j = row % n;
            for (int i = 0; i < n; ++i) {
                const glm::vec2 uv((float(i) + 0.5f) / float(n), (float(j) + 0.5f) / float(n));
                const glm::vec3 dir = glm::normalize(glsl::cubeFaceDirection(face, uv));
                const EnvSample s = tracer.traceEnvironment(centre, dir);
                const std::size_t t = std::size_t((face * n + j) * n + i);
                radiance[t] = s.radiance;
                if (s.hit && std::isfinite(s.distance) && s.distance > 0.f)
                    g.distances[t] = s.distance;
            }
        }
    });

    choosePemDistanceSearch(g);
    if (capturedRadiance) *capturedRadiance = std::move(radiance);
    return g;
}

void choosePemDistanceSearch(PemDistanceGeometry& g) {
    if (!(g.dInf > 0.f) || !std::isfinite(g.dInf))
        throw Error("", "d_inf", "expected a finite d_inf > 0");
    float maxD = 0.f;
    for (float d : g.distances)
        if (d != g.dInf) maxD = std::max(maxD, d); // a hit beyond d_inf fails below
    if (!(g.dInf > 2.1f * maxD)) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "expected d_inf above 2.1 x the largest distance, %g m",
                      double(maxD));
        throw Error("", "d_inf", buf);
    }
    // See the header for why these.
    g.range = maxD > 0.f ? 1.05f * maxD : 1.f;
    g.tolerance = 1e-3f * g.range;
    g.maxSteps = bisectionSteps(g.range, g.tolerance);
}

} // namespace specula
