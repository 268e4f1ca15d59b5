#include "assetcooker/lib/flavours/pem/pem_rounding_rows.h"

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace specula {

namespace {

// A lookup's weights by texel index (PemWeights lists each texel once).
using TexelWeights = std::vector<std::pair<int, float>>;

TexelWeights lookupWeights(const PemLookupCpu& lookup, glm::vec3 x, glm::vec3 l,
                           const PemFootprint& f) {
    TexelWeights w;
    lookup.weights(x, l, w, f);
    std::sort(w.begin(), w.end());
    return w;
}

// Half the L1 distance between two lookups' weights: 0 for the same texels read alike, 1 for
// disjoint texels. A move across a bilinear cell's edge shifts a little weight (no row
// needed: the texels read are nearly those fitted); a search that ends elsewhere moves it all.
float weightShift(const TexelWeights& a, const TexelWeights& b) {
    float sum = 0.f;
    std::size_t i = 0, j = 0;
    while (i < a.size() || j < b.size()) {
        if (j == b.size() || (i < a.size() && a[i].first < b[j].first)) {
            sum += a[i++].second;
        } else if (i == a.size() || b[j].first < a[i].first) {
            sum += b[j++].second;
        } else {
            sum += std::abs(a[i++].second - b[j++].second);
        }
    }
    return 0.5f * sum;
}

// The ray moved one of twelve ways: x by +-reach along an axis (0..5), l by +-reach along an
// axis and normalised (6..11).
PemSample moved(const PemSample& p, int way, float reach) {
    PemSample q = p;
    const int axis = (way % 6) / 2;
    const float sign = way % 2 == 0 ? 1.f : -1.f;
    if (way < 6) {
        q.x[axis] += sign * reach;
    } else {
        q.l[axis] += sign * reach;
        q.l = glm::normalize(q.l);
    }
    q.pixel = -1;
    q.centre = false;
    return q;
}

} // namespace

PemSamples pemRoundingCopies(const PemLookupCpu& lookup, const PemSamples& samples, float reach) {
    std::vector<PemSamples> perSample(samples.size());
    tbb::parallel_for(std::size_t(0), samples.size(), [&](std::size_t s) {
        const PemSample& p = samples[s];
        const PemFootprint f = p.footprint();
        std::vector<TexelWeights> kept{lookupWeights(lookup, p.x, p.l, f)};
        for (int way = 0; way < 12; ++way) {
            const PemSample q = moved(p, way, reach);
            TexelWeights w = lookupWeights(lookup, q.x, q.l, f);
            if (std::any_of(kept.begin(), kept.end(), [&](const TexelWeights& k) {
                    return weightShift(k, w) <= kPemRoundingShift;
                }))
                continue;
            kept.push_back(std::move(w));
            perSample[s].push_back(q);
        }
    });
    PemSamples out;
    for (PemSamples& copies : perSample)
        out.insert(out.end(), copies.begin(), copies.end());
    return out;
}

} // namespace specula
