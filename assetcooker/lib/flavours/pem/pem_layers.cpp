#include "assetcooker/lib/flavours/pem/pem_layers.h"

#include "engine/core/error.h"
#include "engine/core/flush_denormals.h"

#include <Eigen/Dense>
#include <glm/glm.hpp>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <unordered_set>

namespace specula {

PemCoverage pemCoverage(const PemSamples& samples) {
    PemCoverage c;
    c.rays = samples.size();
    for (const PemSample& s : samples)
        if (!s.onHull) {
            ++c.offHull;
            c.selfHits += s.selfHit ? 1 : 0;
        }
    return c;
}

namespace {

void requirePoints(const std::vector<glm::vec3>& points) {
    if (points.empty())
        throw Error("", "local", "expected reflector points to fit the local sphere to, got none");
    for (const glm::vec3& p : points)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw Error("", "local", "expected finite reflector points");
}

} // namespace

PemLocalSphere boundPemLocalSphere(const std::vector<glm::vec3>& points) {
    requirePoints(points);
    glm::vec3 lo = points.front(), hi = points.front();
    for (const glm::vec3& p : points)
        lo = glm::min(lo, p), hi = glm::max(hi, p);
    PemLocalSphere s;
    s.centre = 0.5f * (lo + hi);
    float r = 0.f;
    for (const glm::vec3& p : points)
        r = std::max(r, glm::length(p - s.centre));
    // A single point still needs a sphere to look up on.
    s.radius = std::max(r, 1e-3f * std::max(1.f, glm::length(s.centre)));
    return s;
}

PemLocalSphere fitPemLocalSphere(const std::vector<glm::vec3>& points) {
    const PemLocalSphere bound = boundPemLocalSphere(points);
    if (points.size() < 4) return bound;
    // Relative to the bounding centre, in units of its radius: a well-scaled 4 x 4 system.
    const glm::dvec3 o(bound.centre);
    const double scale = bound.radius;
    Eigen::Matrix4d ata = Eigen::Matrix4d::Zero();
    Eigen::Vector4d atb = Eigen::Vector4d::Zero();
    for (const glm::vec3& pf : points) {
        const glm::dvec3 p = (glm::dvec3(pf) - o) / scale;
        const Eigen::Vector4d row(2.0 * p.x, 2.0 * p.y, 2.0 * p.z, 1.0);
        ata += row * row.transpose();
        atb += row * glm::dot(p, p);
    }
    Eigen::FullPivLU<Eigen::Matrix4d> lu(ata);
    // Coplanar points leave a direction of centres unconstrained.
    lu.setThreshold(1e-9);
    if (lu.rank() < 4) return bound;
    const Eigen::Vector4d x = lu.solve(atb);
    const glm::dvec3 c(x[0], x[1], x[2]);
    const double r2 = x[3] + glm::dot(c, c);
    if (!(r2 > 0.0) || !(std::sqrt(r2) < 10.0)) return bound;
    PemLocalSphere s;
    s.centre = glm::vec3(o + c * scale);
    s.radius = float(std::sqrt(r2) * scale);
    return s;
}

PemLayers inferPemLayers(const PemSamples& samples, const PemInferOptions& distant,
                         const PemInferOptions& local, const PemLocalSphere& sphere) {
    PemLayers out;
    // A hull ray shows the distant layer alone, so the distant layer must give its full
    // radiance: a grazing hull ray the shading normal turned back into its reflector keeps
    // that bounce rather than the radiance behind the reflector.
    const auto start = std::chrono::steady_clock::now();
    PemSamples d = samples;
    for (PemSample& s : d)
        if (!s.onHull) s.target = s.distant;

    // The local rows' rays: those off the hull; with centre rows, every sub-ray of a pixel
    // whose centre ray leaves off the hull (the pixel draws the composite, its antialiased
    // coverage counting the hull sub-rays as 0). `full`: each one's full radiance (a ray that
    // does not meet its reflector again has distant == target).
    const bool centreRows = local.rows == PemRows::Centre;
    std::unordered_set<int> offHullCentres;
    if (centreRows)
        for (const PemSample& s : samples)
            if (s.centre && !s.onHull && s.pixel >= 0) offHullCentres.insert(s.pixel);
    PemSamples l;
    std::vector<float> alpha;
    std::vector<glm::vec3> full;
    for (const PemSample& s : samples) {
        const bool drawn =
            centreRows && s.pixel >= 0 ? offHullCentres.contains(s.pixel) : !s.onHull;
        if (!drawn) continue;
        const bool self = !s.onHull && s.selfHit;
        PemSample row = s;
        row.target = self ? s.target : glm::vec3(0.f);
        l.push_back(row);
        alpha.push_back(self ? 1.f : 0.f);
        full.push_back(s.target);
    }
    PemInferOptions o = local;
    o.local = sphere;
    o.mipLevels = 1; // the local layer is read at level 0
    o.distance = nullptr;
    o.warmStart = nullptr;
    o.alphaTargets = &alpha;
    // The local prior is 0 (what nobody saw of the reflector reads as the distant layer).
    const std::vector<glm::vec3> zeros(std::size_t(PemMap::texelCount(o.faceRes)), glm::vec3(0.f));
    o.prior = o.priorWeight > 0.f ? &zeros : nullptr;
    if (l.empty()) {
        out.distant = inferPemMap(d, distant);
        out.seconds = out.distant.seconds;
        PemMap& m = out.local.map;
        m.faceRes = o.faceRes;
        m.local = sphere;
        m.texels = zeros;
        m.alpha.assign(zeros.size(), 0.f);
        out.local.unseenTexels = int(zeros.size());
        return out;
    }
    // The distant map and the local layer's first solve read nothing of each other: side by
    // side (the refit below needs both). Denormals flushed on either thread: the same bits
    // whichever runs which (flush_denormals.h).
    tbb::parallel_invoke(
        [&] {
            const ScopedFlushDenormals sameBits;
            out.distant = inferPemMap(d, distant);
        },
        [&] {
            const ScopedFlushDenormals sameBits;
            out.local = inferPemMap(l, o);
        });
    // The solves are apart, but a pixel shows the composite: where the coverage the lookup
    // reads is not the ray's own 0 or 1 (smoothing, bilinear across an alpha edge), the
    // distant layer leaks in. Refit the premultiplied RGB to what the composite still lacks,
    // full - (1 - alpha) distant, given the two maps just inferred (alpha is kept), both
    // looked up where the row's pixel shows them: at each ray, or with centre rows at the
    // pixel's centre ray for all its sub-rays (their mean is then the pixel's target).
    const PemLookupCpu localLookup(out.local.map), distantLookup(out.distant.map);
    const std::vector<std::vector<int>> rows = pemDataRows(l, o.rows);
    for (const std::vector<int>& members : rows)
        for (const int r : members) {
            const PemSample& at = l[std::size_t(centreRows ? members.front() : r)];
            const glm::vec4 over = localLookup.localRadiance(at.x, at.l);
            l[std::size_t(r)].target =
                full[std::size_t(r)] -
                (1.f - over.a) * distantLookup.radiance(at.x, at.l, at.footprint());
        }
    const std::vector<float> keptAlpha = out.local.map.alpha;
    const std::vector<glm::vec3> first = out.local.map.texels;
    o.alphaTargets = nullptr;
    o.warmStart = &first;
    PemInference refit = inferPemMap(l, o);
    refit.map.alpha = keptAlpha;
    refit.seconds += out.local.seconds;
    out.local = std::move(refit);
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

} // namespace specula
