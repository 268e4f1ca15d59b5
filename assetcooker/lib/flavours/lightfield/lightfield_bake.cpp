#include "assetcooker/lib/flavours/lightfield/lightfield_bake.h"

#include "assetcooker/lib/scene/probe_sanity.h"
#include "engine/core/error.h"
#include "engine/core/glsl_host.h"
#include "engine/image/sampling.h"
#include "engine/image_io/image_io.h"
#include "engine/math/shading.h"
#include "engine/raytrace/embree_scene.h"

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

using DepthHistogram = LightFieldDepthHistogram;

std::uint8_t toSrgb8(float linear) {
    const float s = linearToSrgbValue(std::clamp(linear, 0.f, 1.f));
    return std::uint8_t(std::lround(s * 255.f));
}

// The options' checks, the placement check (its warnings to options.warnings).
void checkOptions(ecs::Registry& registry, const SceneMarkup& markup,
                  const LightFieldBakeOptions& opt) {
    validateLightFieldSize(opt.cameras, opt.res, opt.cellSize, opt.compression, "");
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(opt.cellCentre[i]))
            throw Error("", "cell_centre", "expected finite numbers");
    if (!(opt.depthPercentile >= 0.f && opt.depthPercentile <= 0.5f))
        throw Error("", "depthPercentile", "expected [0, 0.5]");
    // The same placement check as the distance bake, so both flavours refuse and accept the
    // same scenes: sky without geometry is legal (every slab holds the sky).
    const std::vector<std::string> warnings =
        checkProbePlacement(registry, markup, opt.cellCentre, opt.sky && !opt.sky->empty());
    if (opt.warnings) opt.warnings->insert(opt.warnings->end(), warnings.begin(), warnings.end());
}

float histogramQMax(const LightFieldBakeOptions& opt) {
    return 1.f / (0.01f * opt.cellSize);
}

// Traces camera (i, j) of `slab` into `rows`, the slab image's row j * res (a stride of
// n = cameras * res pixels), and its through-cell samples into `hist`.
void traceCamera(const EmbreeScene& environment, const LightFieldBakeOptions& opt, int slab, int i,
                 int j, std::uint8_t* rows, DepthHistogram& hist) {
    const int num = opt.cameras, res = opt.res, n = num * res;
    const float h = 0.5f * opt.cellSize;
    const int a = slab / 2, b = (a + 1) % 3, c = (a + 2) % 3;
    const float sigma = slab % 2 ? -1.f : 1.f;
    glm::vec3 camera(0.f);
    camera[a] = sigma * h;
    camera[b] = (float(i) / float(num - 1) - 0.5f) * 6.f * h;
    camera[c] = (float(j) / float(num - 1) - 0.5f) * 6.f * h;
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) {
            // The unnormalised direction has |d_a| = 1, so Embree's t (in units of |dir|) plus
            // the start offset is the axial depth from the camera plane.
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
                radiance = glm::vec3(sampleBilinear(*opt.sky, glsl::equirectUv(glm::normalize(dir)),
                                                    Wrap::Repeat, Wrap::Clamp));
            }
            if (throughCell) hist.add(hit ? tau + hit->t : 0.f, bool(hit));
            std::uint8_t* p = &rows[(std::size_t(y) * n + std::size_t(i * res + x)) * 3];
            p[0] = toSrgb8(radiance.r), p[1] = toSrgb8(radiance.g), p[2] = toSrgb8(radiance.b);
        }
}

// Traces the cameras [0, cameras) x [j0, j1) of each slab in `slabs` into the images
// (`rgb[slab]`, whose first byte is camera row j0's) and histograms, in parallel; progress
// goes from 0 to `progressTo`.
void traceCameras(const EmbreeScene& environment, const LightFieldBakeOptions& opt,
                  const std::vector<int>& slabs, int j0, int j1,
                  std::array<std::vector<std::uint8_t>, 6>& rgb,
                  std::array<DepthHistogram, 6>& hist, double progressTo) {
    const int num = opt.cameras, rows = j1 - j0, n = num * opt.res;
    std::mutex histMutex;
    const long perSlab = long(rows) * num;
    const long tasks = long(slabs.size()) * perSlab;
    std::atomic<long> done{0};
    std::atomic<bool> stop{false};
    tbb::parallel_for(tbb::blocked_range<long>(0, tasks), [&](const tbb::blocked_range<long>& r) {
        std::array<DepthHistogram, 6> local;
        for (auto& H : local)
            H.qMax = histogramQMax(opt);
        bool used[6] = {};
        for (long task = r.begin(); task < r.end(); ++task) {
            if (stop || (opt.cancelled && opt.cancelled())) {
                stop = true;
                break;
            }
            const int slab = slabs[std::size_t(task / perSlab)];
            const int cam = int(task % perSlab);
            const int i = cam % num, j = j0 + cam / num;
            used[slab] = true;
            traceCamera(environment, opt, slab, i, j,
                        &rgb[std::size_t(slab)][std::size_t(j - j0) * opt.res * n * 3],
                        local[std::size_t(slab)]);
            const long d = ++done;
            if (opt.progress && d % 8 == 0) opt.progress(progressTo * double(d) / double(tasks));
        }
        std::lock_guard lock(histMutex);
        for (int k = 0; k < 6; ++k)
            if (used[k]) hist[std::size_t(k)].merge(local[std::size_t(k)]);
    });
    if (stop) throw Error("bake", "", "cancelled");
}

// options.blocks laid into whole slab images and histograms; Error naming what is wrong.
void assembleBlocks(const LightFieldBakeOptions& opt, std::array<std::vector<std::uint8_t>, 6>& rgb,
                    std::array<DepthHistogram, 6>& hist) {
    const int num = opt.cameras, res = opt.res;
    std::array<std::vector<int>, 6> owner;
    for (auto& o : owner)
        o.assign(std::size_t(num), -1);
    const std::vector<LightFieldRows>& blocks = *opt.blocks;
    for (std::size_t k = 0; k < blocks.size(); ++k) {
        const LightFieldRows& b = blocks[k];
        const std::string field = "blocks[" + std::to_string(k) + "]";
        if (b.cameras != num || b.res != res)
            throw Error("", field,
                        "has " + std::to_string(b.cameras) + " cameras of " +
                            std::to_string(b.res) + " px, the bake " + std::to_string(num) +
                            " of " + std::to_string(res));
        if (b.slab < 0 || b.slab >= 6 || b.j0 < 0 || b.j1 <= b.j0 || b.j1 > num)
            throw Error("", field,
                        "expected a slab 0 .. 5 and camera rows 0 <= j0 < j1 <= " +
                            std::to_string(num));
        if (b.rgb.size() != lightFieldRowsBytes(num, res, b.j0, b.j1) ||
            b.histogram.bins.size() != std::size_t(DepthHistogram::kBins))
            throw Error("", field, "has the wrong number of bytes or histogram bins");
        if (b.histogram.qMax != histogramQMax(opt))
            throw Error("", field, "has a depth histogram of another cell size");
        for (int j = b.j0; j < b.j1; ++j) {
            int& o = owner[std::size_t(b.slab)][std::size_t(j)];
            if (o >= 0)
                throw Error("", field,
                            "slab " + std::to_string(b.slab) + " camera row " + std::to_string(j) +
                                " is also in blocks[" + std::to_string(o) + "] (overlapping)");
            o = int(k);
        }
    }
    std::string missing;
    for (int s = 0; s < 6; ++s)
        for (int j = 0; j < num; ++j)
            if (owner[std::size_t(s)][std::size_t(j)] < 0)
                missing += (missing.empty() ? "" : ", ") + std::string("slab ") +
                           std::to_string(s) + " row " + std::to_string(j);
    if (!missing.empty()) throw Error("", "blocks", "camera rows missing: " + missing);
    const std::size_t rowBytes = lightFieldRowsBytes(num, res, 0, 1);
    for (const LightFieldRows& b : blocks) {
        std::copy(b.rgb.begin(), b.rgb.end(),
                  rgb[std::size_t(b.slab)].begin() + std::ptrdiff_t(rowBytes * std::size_t(b.j0)));
        hist[std::size_t(b.slab)].merge(b.histogram);
    }
}

} // namespace

LightFieldAsset bakeLightFieldProbe(ecs::Registry& registry, const SceneMarkup& markup,
                                    const LightFieldBakeOptions& opt) {
    const auto start = std::chrono::steady_clock::now();
    checkOptions(registry, markup, opt);

    LightFieldAsset asset;
    asset.cellCentre = opt.cellCentre;
    asset.cellSize = opt.cellSize;
    asset.cameras = opt.cameras;
    asset.res = opt.res;
    asset.compression = opt.compression;
    asset.depthPercentile = opt.depthPercentile;
    asset.intrusions = findLightFieldIntrusions(markup, opt.cellCentre, opt.cellSize);

    const int num = opt.cameras, n = num * opt.res;
    std::array<std::vector<std::uint8_t>, 6> rgb;
    std::array<DepthHistogram, 6> hist;
    for (auto& layer : rgb)
        layer.assign(std::size_t(n) * n * 3, 0);
    for (auto& H : hist)
        H.qMax = histogramQMax(opt);
    if (opt.blocks) {
        assembleBlocks(opt, rgb, hist);
    } else {
        const auto& mirrors = markup.mirrorEntities;
        const EmbreeScene environment(registry, [&](ecs::Entity e) { return !mirrors.count(e); });
        traceCameras(environment, opt, {0, 1, 2, 3, 4, 5}, 0, num, rgb, hist, 0.95);
    }

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

LightFieldRows traceLightFieldRows(ecs::Registry& registry, const SceneMarkup& markup,
                                   const LightFieldBakeOptions& opt, int slab, int j0, int j1) {
    checkOptions(registry, markup, opt);
    if (slab < 0 || slab >= 6) throw Error("", "slab", "expected 0 .. 5");
    if (j0 < 0 || j1 <= j0 || j1 > opt.cameras)
        throw Error("", "rows",
                    "expected camera rows 0 <= j0 < j1 <= " + std::to_string(opt.cameras) +
                        ", got " + std::to_string(j0) + " .. " + std::to_string(j1));
    const auto& mirrors = markup.mirrorEntities;
    const EmbreeScene environment(registry, [&](ecs::Entity e) { return !mirrors.count(e); });
    std::array<std::vector<std::uint8_t>, 6> rgb;
    std::array<DepthHistogram, 6> hist;
    rgb[std::size_t(slab)].assign(lightFieldRowsBytes(opt.cameras, opt.res, j0, j1), 0);
    for (auto& H : hist)
        H.qMax = histogramQMax(opt);
    traceCameras(environment, opt, {slab}, j0, j1, rgb, hist, 1.0);
    LightFieldRows out;
    out.slab = slab, out.j0 = j0, out.j1 = j1, out.cameras = opt.cameras, out.res = opt.res;
    out.histogram = std::move(hist[std::size_t(slab)]);
    out.rgb = std::move(rgb[std::size_t(slab)]);
    if (opt.progress) opt.progress(1.0);
    return out;
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
