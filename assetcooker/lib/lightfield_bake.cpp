#include "lightfield_bake.h"

#include "assetcooker/lib/probe_sanity.h"
#include "engine/core/error.h"
#include "engine/core/glsl_host.h"
#include "engine/image/image_io.h"
#include "engine/image/sampling.h"
#include "engine/raytrace/embree_scene.h"
#include "engine/scene/shading.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>

namespace specula {

namespace {

// Depth statistics of one slab over the samples whose line passes through the cell, binned
// in inverse depth (disparity is linear in 1/z, so that is where the percentiles matter).
struct DepthHistogram {
    static constexpr int kBins = 8192;
    float qMax = 1.f; // 1 / the nearest depth binned apart
    std::vector<std::uint64_t> bins = std::vector<std::uint64_t>(kBins, 0);
    std::uint64_t sky = 0, intruding = 0, total = 0;
    float minDepth = std::numeric_limits<float>::infinity(), maxDepth = 0.f;

    void add(float depth, bool hit) {
        ++total;
        if (!hit) {
            ++sky;
            return;
        }
        if (!(depth > 0.f)) {
            ++intruding;
            return;
        }
        minDepth = std::min(minDepth, depth);
        maxDepth = std::max(maxDepth, depth);
        const int bin = std::min(int(1.f / depth / qMax * float(kBins)), kBins - 1);
        ++bins[std::size_t(bin)];
    }
    void merge(const DepthHistogram& o) {
        for (int i = 0; i < kBins; ++i)
            bins[std::size_t(i)] += o.bins[std::size_t(i)];
        sky += o.sky, intruding += o.intruding, total += o.total;
        minDepth = std::min(minDepth, o.minDepth);
        maxDepth = std::max(maxDepth, o.maxDepth);
    }
    // Inverse depth at fraction f of the samples beyond the plane, the sky counting as q = 0.
    float quantileQ(double f) const {
        const std::uint64_t n = total - intruding;
        if (n == 0) return 0.f;
        const double want = f * double(n);
        double seen = double(sky);
        if (seen > want) return 0.f;
        for (int i = 0; i < kBins; ++i) {
            seen += double(bins[std::size_t(i)]);
            if (seen > want) return (float(i) + 0.5f) / float(kBins) * qMax;
        }
        return qMax;
    }
};

std::uint8_t toSrgb8(float linear) {
    const float s = linearToSrgbValue(std::clamp(linear, 0.f, 1.f));
    return std::uint8_t(std::lround(s * 255.f));
}

} // namespace

LightFieldAsset bakeLightFieldProbe(ecs::Registry& registry, const SceneMarkup& markup,
                                    const LightFieldBakeOptions& opt) {
    validateLightFieldSize(opt.cameras, opt.res, opt.cellSize, opt.compression, "");
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(opt.cellCentre[i]))
            throw Error("", "cell_centre", "expected finite numbers");
    if (!(opt.depthPercentile >= 0.f && opt.depthPercentile <= 0.5f))
        throw Error("", "depthPercentile", "expected [0, 0.5]");
    const auto start = std::chrono::steady_clock::now();

    // The same placement check as the distance bake, so both flavours refuse and accept the
    // same scenes: sky without geometry is legal (every slab holds the sky).
    const std::vector<std::string> warnings =
        checkProbePlacement(registry, markup, opt.cellCentre, opt.sky && !opt.sky->empty());
    if (opt.warnings) opt.warnings->insert(opt.warnings->end(), warnings.begin(), warnings.end());
    const auto& mirrors = markup.mirrorEntities;
    const EmbreeScene environment(registry, [&](ecs::Entity e) { return !mirrors.count(e); });

    LightFieldAsset asset;
    asset.cellCentre = opt.cellCentre;
    asset.cellSize = opt.cellSize;
    asset.cameras = opt.cameras;
    asset.res = opt.res;
    asset.compression = opt.compression;
    asset.depthPercentile = opt.depthPercentile;
    asset.intrusions = findLightFieldIntrusions(markup, opt.cellCentre, opt.cellSize);

    const int num = opt.cameras, res = opt.res, n = num * res;
    const float h = 0.5f * opt.cellSize;
    std::array<std::vector<std::uint8_t>, 6> rgb;
    std::array<DepthHistogram, 6> hist;
    for (auto& layer : rgb)
        layer.assign(std::size_t(n) * n * 3, 0);
    for (auto& H : hist)
        H.qMax = 1.f / (0.01f * opt.cellSize);
    std::mutex histMutex;
    const long tasks = 6L * num * num;
    std::atomic<long> done{0};
    std::atomic<bool> stop{false};

    tbb::parallel_for(tbb::blocked_range<long>(0, tasks), [&](const tbb::blocked_range<long>& r) {
        std::array<DepthHistogram, 6> local;
        for (auto& H : local)
            H.qMax = hist[0].qMax;
        bool used[6] = {};
        for (long task = r.begin(); task < r.end(); ++task) {
            if (stop || (opt.cancelled && opt.cancelled())) {
                stop = true;
                break;
            }
            const int slab = int(task / (long(num) * num));
            const int cam = int(task % (long(num) * num));
            const int i = cam % num, j = cam / num;
            const int a = slab / 2, b = (a + 1) % 3, c = (a + 2) % 3;
            const float sigma = slab % 2 ? -1.f : 1.f;
            glm::vec3 camera(0.f);
            camera[a] = sigma * h;
            camera[b] = (float(i) / float(num - 1) - 0.5f) * 6.f * h;
            camera[c] = (float(j) / float(num - 1) - 0.5f) * 6.f * h;
            used[slab] = true;
            for (int y = 0; y < res; ++y)
                for (int x = 0; x < res; ++x) {
                    // The unnormalised direction has |d_a| = 1, so Embree's t (in units of
                    // |dir|) plus the start offset is the axial depth from the camera plane.
                    glm::vec3 dir(0.f);
                    dir[a] = sigma;
                    dir[b] = (float(x) + 0.5f) * 2.f / float(res) - 1.f;
                    dir[c] = (float(y) + 0.5f) * 2.f / float(res) - 1.f;
                    // Where the line leaves the cell (slab test, tau <= 0), if it meets it.
                    float t0 = -std::numeric_limits<float>::infinity();
                    float t1 = std::numeric_limits<float>::infinity();
                    for (int k = 0; k < 3; ++k) {
                        if (dir[k] == 0.f) {
                            if (std::abs(camera[k]) > h) t0 = 1.f, t1 = 0.f;
                            continue;
                        }
                        const float ta = (-h - camera[k]) / dir[k], tb = (h - camera[k]) / dir[k];
                        t0 = std::max(t0, std::min(ta, tb));
                        t1 = std::min(t1, std::max(ta, tb));
                    }
                    const bool throughCell = t0 <= t1;
                    const float tau = throughCell ? std::min(t1, 0.f) : 0.f;
                    const glm::vec3 origin = opt.cellCentre + camera + tau * dir;
                    glm::vec3 radiance(0.f);
                    const auto hit = environment.intersect(origin, dir, 0.f);
                    if (hit) {
                        radiance = glsl::shadeSurface(hit->albedo, hit->normal);
                    } else if (opt.sky && !opt.sky->empty()) {
                        radiance = glm::vec3(sampleBilinear(*opt.sky,
                                                            glsl::equirectUv(glm::normalize(dir)),
                                                            Wrap::Repeat, Wrap::Clamp));
                    }
                    if (throughCell) local[slab].add(hit ? tau + hit->t : 0.f, bool(hit));
                    std::uint8_t* p =
                        &rgb[std::size_t(slab)]
                            [(std::size_t(j * res + y) * n + std::size_t(i * res + x)) * 3];
                    p[0] = toSrgb8(radiance.r), p[1] = toSrgb8(radiance.g),
                    p[2] = toSrgb8(radiance.b);
                }
            const long d = ++done;
            if (opt.progress && d % 8 == 0) opt.progress(0.95 * double(d) / double(tasks));
        }
        std::lock_guard lock(histMutex);
        for (int k = 0; k < 6; ++k)
            if (used[k]) hist[std::size_t(k)].merge(local[std::size_t(k)]);
    });
    if (stop) throw Error("bake", "", "cancelled");

    tbb::parallel_for(0, 6, [&](int k) {
        LightFieldSlab& s = asset.slabs[std::size_t(k)];
        const DepthHistogram& H = hist[std::size_t(k)];
        const float qFar = H.quantileQ(opt.depthPercentile);
        const float qNear = H.quantileQ(1.0 - opt.depthPercentile);
        const float inf = std::numeric_limits<float>::infinity();
        s.nearDepth = qNear > 0.f ? 1.f / qNear : inf;
        s.farDepth = qFar > 0.f ? 1.f / qFar : inf;
        s.minDepth = std::isfinite(H.minDepth) ? H.minDepth : 0.f;
        s.maxDepth = H.maxDepth;
        s.skyFraction = H.total ? float(double(H.sky) / double(H.total)) : 0.f;
        s.intrudingFraction = H.total ? float(double(H.intruding) / double(H.total)) : 0.f;
        // Plenoptic sampling: the focal plane at the harmonic mean of near and far, i.e. the
        // midpoint of their disparities (an infinite far depth has disparity 0).
        const float qFocal = 0.5f * (qNear + qFar);
        s.focalDepth = qFocal > 0.f ? 1.f / qFocal : inf;
        s.disparity = disparityForDepth(asset, s.focalDepth);
        s.data = opt.compression == LightFieldCompression::BC1
                     ? encodeBC1(rgb[std::size_t(k)].data(), n, n)
                     : std::move(rgb[std::size_t(k)]);
    });
    asset.bakeSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (opt.progress) opt.progress(1.0);
    return asset;
}

std::vector<LightFieldIntrusion> findLightFieldIntrusions(const SceneMarkup& markup,
                                                          glm::vec3 centre, float cellSize) {
    const float h = 0.5f * cellSize;
    std::vector<LightFieldIntrusion> out;
    for (const EnvironmentObject& o : markup.objects) {
        if (o.bounds.empty()) continue; // no geometry
        const Aabb box = o.bounds.translated(-centre);
        // The bounds' point nearest the cell centre, and its Chebyshev distance past the
        // cell surface.
        const glm::vec3 q = glm::clamp(glm::vec3(0.f), box.min, box.max);
        const float depth = h - std::max(std::abs(q.x), std::max(std::abs(q.y), std::abs(q.z)));
        if (depth > 0.f) {
            out.push_back({o.name, "cell", depth});
            continue;
        }
        // Slab pair a: rays leave the cell through x_a = +-h after crossing the box
        // [-h, h] on a and [-3h, 3h] on the other axes.
        for (int a = 0; a < 3; ++a) {
            glm::vec3 e(3.f * h);
            e[a] = h;
            if (box.overlaps({-e, e}))
                out.push_back({o.name, std::string("slabs +-") + "XYZ"[a], depth});
        }
    }
    return out;
}

std::vector<ReflectorOverhang> findReflectorOverhangs(const ecs::Registry& registry,
                                                      const SceneMarkup& markup, glm::vec3 centre,
                                                      float cellSize) {
    const float h = 0.5f * cellSize;
    std::vector<ReflectorOverhang> out;
    for (const ReflectorMarkup& r : markup.reflectors) {
        Aabb bounds;
        for (ecs::Entity e : r.meshes)
            bounds.extend(meshWorldBounds(registry, e));
        const float over = bounds.overhang(Aabb::cube(centre, h));
        if (over > 0.f) out.push_back({r.node, over});
    }
    return out;
}

} // namespace specula
