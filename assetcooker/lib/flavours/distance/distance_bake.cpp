#include "assetcooker/lib/flavours/distance/distance_bake.h"
#include "assetcooker/lib/os/memory_estimate.h"

#include "assetcooker/lib/scene/probe_sanity.h"
#include "components/reflection_probe/distance/distance_lookup_config.h"
#include "components/reflection_probe/distance/distance_probe.h"
#include "engine/core/error.h"
#include "engine/core/glsl_host.h"
#include "engine/image/sampling.h"
#include "engine/math/cube_face.h"
#include "engine/math/shading.h"
#include "engine/raytrace/embree_scene.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <iterator>
#include <limits>
#include <unordered_map>

namespace specula {

namespace {

constexpr float kMiss = -1.f; // marks texels with no hit until d_inf is known

struct LayerStats {
    double weightedSum = 0, weight = 0;
    float minD = std::numeric_limits<float>::max(), maxD = 0;
};

// Renders one layer's six faces against `scene`; texels that see nothing get sky (when
// given) and kMiss in alpha.
void bakeFaces(const EmbreeScene& scene, const DistanceBakeOptions& opt, bool withSky,
               std::array<Image, 6>& faces, std::atomic<long>& rowsDone, long rowsTotal) {
    const int n = opt.faceRes;
    for (int f = 0; f < 6; ++f) {
        faces[std::size_t(f)] = Image(n, n, 4);
        Image& img = faces[std::size_t(f)];
        tbb::parallel_for(tbb::blocked_range<int>(0, n), [&](const tbb::blocked_range<int>& r) {
            for (int y = r.begin(); y < r.end(); ++y) {
                if (opt.cancelled && opt.cancelled()) return;
                for (int x = 0; x < n; ++x) {
                    const glm::vec2 uv((float(x) + 0.5f) / float(n), (float(y) + 0.5f) / float(n));
                    const glm::vec3 dir = glm::normalize(glsl::cubeFaceDirection(f, uv));
                    glm::vec3 rgb(0.f);
                    float d = kMiss;
                    if (auto hit = scene.intersect(opt.centre, dir, 0.f)) {
                        rgb = glsl::shadeSurface(hit->albedo, hit->normal);
                        d = hit->t;
                    } else if (withSky && opt.sky && !opt.sky->empty()) {
                        rgb = glm::vec3(sampleBilinear(*opt.sky, glsl::equirectUv(dir),
                                                       Wrap::Repeat, Wrap::Clamp));
                    }
                    float* p = img.at(x, y);
                    p[0] = rgb.r, p[1] = rgb.g, p[2] = rgb.b, p[3] = d;
                }
                const long done = ++rowsDone;
                if (opt.progress && done % 16 == 0) opt.progress(double(done) / double(rowsTotal));
            }
        });
        if (opt.cancelled && opt.cancelled()) throw Error("bake", "", "cancelled");
    }
}

LayerStats statsOf(const std::array<Image, 6>& faces) {
    LayerStats s;
    const int n = faces[0].width;
    for (const Image& img : faces)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const float d = img.at(x, y)[3];
                if (d == kMiss) continue;
                const float w = float(cubeTexelSolidAngle(x, y, n));
                s.weightedSum += double(w) * d;
                s.weight += w;
                s.minD = std::min(s.minD, d);
                s.maxD = std::max(s.maxD, d);
            }
    return s;
}

void setInfinity(std::array<Image, 6>& faces, float dInf) {
    for (Image& img : faces)
        for (std::size_t i = 3; i < img.pixels.size(); i += 4)
            if (img.pixels[i] == kMiss) img.pixels[i] = dInf;
}

} // namespace

DistanceProbeAsset bakeDistanceProbe(ecs::Registry& registry, const SceneMarkup& markup,
                                     const DistanceBakeOptions& opt) {
    if (opt.faceRes < 1 || opt.faceRes > 4096)
        throw Error("", "face_res", "expected 1 to 4096, got " + std::to_string(opt.faceRes));
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(opt.centre[i])) throw Error("", "centre", "expected finite numbers");

    // Refuses nothing to reflect (no geometry met, no sky) and probes inside solids or on
    // surfaces; an environment of sky alone is legal (every texel misses).
    const bool sky = opt.withSky && opt.sky && !opt.sky->empty();
    const std::vector<std::string> warnings =
        checkProbePlacement(registry, markup, opt.centre, sky);
    if (opt.warnings) opt.warnings->insert(opt.warnings->end(), warnings.begin(), warnings.end());
    const auto& mirrors = markup.mirrorEntities;
    const EmbreeScene environment(registry, [&](ecs::Entity e) { return !mirrors.count(e); });

    const std::size_t layerCount = opt.compositeOnly    ? 0
                                   : opt.layers.empty() ? markup.objects.size()
                                                        : opt.layers.size();
    // Refused before any face is rendered: what the runtime would refuse to read, and what
    // would not fit in memory.
    if (layerCount > std::size_t(glsl::kMaxDistanceLayers - 1))
        throw Error("", "layers",
                    std::to_string(layerCount) +
                        " object layers (one per object): the runtime reads "
                        "at most " +
                        std::to_string(glsl::kMaxDistanceLayers - 1) +
                        "; bake with --layers plan, which packs objects into shared layers");
    checkMemoryFor(cubeLayersBytes(opt.faceRes, 1 + layerCount),
                   "a bake at face_res " + std::to_string(opt.faceRes) + " with " +
                       std::to_string(1 + layerCount) + " layers",
                   "", "face_res");
    const long rowsTotal = long(opt.faceRes) * 6 * long(1 + layerCount);
    std::atomic<long> rowsDone{0};

    DistanceProbeAsset asset;
    asset.centre = opt.centre;
    asset.faceRes = opt.faceRes;
    if (opt.sky) asset.sky = *opt.sky;

    DistanceProbeLayer composite;
    composite.name = "composite";
    composite.method = opt.compositeMethod;
    for (const EnvironmentObject& o : markup.objects)
        composite.objects.push_back(o.name);
    bakeFaces(environment, opt, opt.withSky, composite.faces, rowsDone, rowsTotal);

    // The layers: the plan's groups, or one per object.
    std::vector<DistanceBakeOptions::LayerSpec> specs = opt.layers;
    if (specs.empty() && !opt.compositeOnly)
        for (const EnvironmentObject& o : markup.objects)
            specs.push_back({o.name, {o.name}, ""});
    std::vector<DistanceProbeLayer> objects;
    // By name, once: a search per layer made many-layer bakes quadratic.
    std::unordered_map<std::string, const EnvironmentObject*> byName;
    for (const EnvironmentObject& o : markup.objects)
        byName.emplace(o.name, &o);
    for (const DistanceBakeOptions::LayerSpec& spec : specs) {
        std::unordered_set<ecs::Entity> members;
        Aabb bounds;
        for (const std::string& name : spec.objects) {
            const auto found = byName.find(name);
            if (found == byName.end())
                throw Error("", "layer '" + spec.name + "'", "names unknown object '" + name + "'");
            const EnvironmentObject& o = *found->second;
            members.insert(o.meshes.begin(), o.meshes.end());
            bounds.extend(o.bounds);
        }
        const EmbreeScene scene(registry, [&](ecs::Entity e) { return members.count(e) > 0; });
        DistanceProbeLayer layer;
        layer.name = spec.name;
        layer.objects = spec.objects;
        layer.method = spec.method;
        // Grown a little: a ray grazing the bounds must still try the layer.
        layer.boxMin = bounds.min - opt.centre - glm::vec3(1e-3f);
        layer.boxMax = bounds.max - opt.centre + glm::vec3(1e-3f);
        bakeFaces(scene, opt, false, layer.faces, rowsDone, rowsTotal);
        objects.push_back(std::move(layer));
    }

    auto finish = [&](DistanceProbeLayer& L) {
        const LayerStats s = statsOf(L.faces);
        L.solidAngle = float(s.weight);
        L.avgDistance = s.weight > 0 ? float(s.weightedSum / s.weight) : 0.f;
        L.minDistance = s.weight > 0 ? s.minD : 0.f;
        L.maxDistance = s.maxD;
        if (L.method.empty())
            L.method = L.solidAngle >= opt.rectifySolidAngle ? toString(DistanceMethod::Bisection)
                                                             : toString(DistanceMethod::AvgDist);
        return s;
    };
    const LayerStats all = finish(composite);
    for (DistanceProbeLayer& L : objects)
        finish(L);

    // d_inf must exceed every distance a lookup can meet; D must reach every hit from any
    // reflector point within the reach (docs/design.md §4: the hit lies within (x, x + 2D)).
    asset.dInf = std::max(1000.f, 10.f * all.maxD);
    asset.range = 0.5f * (all.maxD + opt.reflectorReach) * 1.05f;
    setInfinity(composite.faces, asset.dInf);
    for (DistanceProbeLayer& L : objects)
        setInfinity(L.faces, asset.dInf);

    if (opt.layers.empty()) {
        // Near to far by the nearest point of each object: the order occlusion needs.
        std::stable_sort(objects.begin(), objects.end(),
                         [](const DistanceProbeLayer& a, const DistanceProbeLayer& b) {
                             return a.minDistance < b.minDistance;
                         });
        // An object the probe cannot see at all adds nothing but cost.
        std::erase_if(objects, [](const DistanceProbeLayer& L) { return L.solidAngle <= 0.f; });
    }

    Aabb envBounds;
    for (const EnvironmentObject& o : markup.objects)
        envBounds.extend(o.bounds);
    const Aabb& box = opt.proxy ? *opt.proxy : envBounds;
    asset.boxMin = box.min - opt.centre;
    asset.boxMax = box.max - opt.centre;
    composite.boxMin = asset.boxMin;
    composite.boxMax = asset.boxMax;

    asset.layers.push_back(std::move(composite));
    for (DistanceProbeLayer& L : objects)
        asset.layers.push_back(std::move(L));
    if (opt.progress) opt.progress(1.0);
    return asset;
}

bool hasGlossyReflector(const SceneMarkup& markup) {
    return std::any_of(markup.reflectors.begin(), markup.reflectors.end(),
                       [](const ReflectorMarkup& r) { return r.roughness > 0.f; });
}

void prefilterComposite(DistanceProbeAsset& asset, const GgxPrefilterOptions& options) {
    if (asset.layers.empty()) throw Error("", "layers", "expected the composite to prefilter");
    GgxPrefilterOptions o = options;
    o.dInf = asset.dInf;
    CubeChain chain = prefilterGgx(asset.layers[0].faces, o);
    // Level 0 is the composite itself; the asset keeps the levels above it.
    asset.glossyLevels.assign(std::make_move_iterator(chain.levels.begin() + 1),
                              std::make_move_iterator(chain.levels.end()));
}

} // namespace specula
