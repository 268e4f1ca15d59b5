#include "pem_samples.h"

#include "assetcooker/lib/pem_geometry.h"
#include "assetcooker/lib/pem_layers.h"
#include "components/reflection_probe/pem/pem_blend.h"
#include "components/reflection_probe/pem/pem_probe_cpu.h"
#include "components/reflection_probe/walk_path.h"
#include "engine/core/error.h"
#include "engine/scene/mesh_bounds.h"

#include <optional>
#include <unordered_map>

namespace specula {

namespace {

// The scene at parameter t: parameter "viewpoint" moves the camera along the walk's orbit
// (walkOrbitCameraView) past reflectors that stay put, so one tracer serves every t;
// parameter "reflector" moves the reflectors along the walk path (walkOffset) before a fixed
// camera (the orbit's t = 0, the scene camera), so each t gets a tracer of the moved scene.
// The reflectors are back where the scene authors them when the state goes.
class PemParameterState {
public:
    struct At {
        const GroundTruthTracer* tracer;
        CameraView camera;
    };

    PemParameterState(ProbeScene& scene, const PemCookSettings& s)
        : scene_(scene), s_(s), byReflector_(s.parameter == "reflector"), roots_(scene) {
        if (!byReflector_) {
            tracer_.emplace(scene.registry, groundTruthOptions(scene, false));
            return;
        }
        parseWalkPath(s.path, path_); // validated
        amplitude_ = walkAmplitude(scene, glm::vec3(0.f));
        if (!(amplitude_ > 0.f))
            throw Error(scene.path, "parameter",
                        "the reflectors have no room to move inside the probe's cell (cell_size)");
    }
    ~PemParameterState() {
        if (byReflector_) roots_.setOffset(scene_.registry, glm::vec3(0.f));
    }
    PemParameterState(const PemParameterState&) = delete;
    PemParameterState& operator=(const PemParameterState&) = delete;

    At at(float t) {
        if (!byReflector_)
            return {&*tracer_, walkOrbitCameraView(scene_, s_.imageWidth, s_.imageHeight, t)};
        roots_.setOffset(scene_.registry, walkOffset(path_, t, amplitude_));
        tracer_.reset(); // one Embree scene at a time
        tracer_.emplace(scene_.registry, groundTruthOptions(scene_, false));
        return {&*tracer_, walkOrbitCameraView(scene_, s_.imageWidth, s_.imageHeight, 0.f)};
    }

private:
    ProbeScene& scene_;
    const PemCookSettings& s_;
    bool byReflector_;
    ReflectorRoots roots_;
    WalkPath path_ = WalkPath::Orbit;
    float amplitude_ = 0.f;
    std::optional<GroundTruthTracer> tracer_;
};

// Each sample's fit half-way to the next one: the two maps blended as the runtime blends them
// (pemBlend; the paths are closed loops, so the last sample blends with the first) against
// the tracer at that viewpoint.
void measureOffManifold(const PemAsset& asset, const PemCookSettings& s, const PemCookHooks& hooks,
                        const std::string& file, const std::function<PemSamples(float)>& trace) {
    std::vector<float> params;
    for (const PemSampleMap& m : asset.samples)
        params.push_back(m.parameter);
    const bool periodic = true; // every walk path is a closed loop (walk_path.h)
    for (int k = 0; k < s.samples; ++k) {
        if (hooks.cancelled && hooks.cancelled())
            throw Error(file, "cancelled", "the bake was cancelled");
        const float t = (float(k) + 0.5f) / float(s.samples);
        const PemBlendWeights w = pemBlend(params, t, false, periodic);
        // The runtime's own twin: the blend, and the local layer off the hull.
        glsl::PemParams block = pemParams(asset, PemProbe{});
        block.layerA = 6 * w.a;
        block.layerB = 6 * w.b;
        block.wb = w.wb;
        const PemProbeCpu twin(asset, block);
        (*hooks.fits)[std::size_t(k)].psnrOff = pemSamplesPsnr(
            trace(t), [&](const PemSample& p) { return twin.radiance(p.x, p.l, p.onHull); });
        if (hooks.progress) hooks.progress(0.5 + 0.5 * double(k + 1) / double(s.samples));
    }
}

// One sample's maps as the runtime draws them at that sample: the distant map, with the
// local layer over it off the hull.
glm::vec3 sampleRadiance(const PemSampleMap& m, bool localLayer, const PemSample& p) {
    const glm::vec3 distant = PemLookupCpu(m.map).radiance(p.x, p.l);
    if (!localLayer || p.onHull) return distant;
    const glm::vec4 local = PemLookupCpu(m.local).localRadiance(p.x, p.l);
    return glm::vec3(local) + (1.f - local.a) * distant;
}

// The local sphere from every sample's off-hull reflector points (all points when none is
// off the hull: an "on" layer then only ever reads alpha 0), by PemCookSettings::localSphere.
PemLocalSphere localSphereOf(const std::vector<PemSamples>& traced, bool fit) {
    std::vector<glm::vec3> points, all;
    for (const PemSamples& samples : traced)
        for (const PemSample& p : samples) {
            all.push_back(p.x);
            if (!p.onHull) points.push_back(p.x);
        }
    if (points.empty()) return boundPemLocalSphere(all);
    return fit ? fitPemLocalSphere(points) : boundPemLocalSphere(points);
}

} // namespace

Aabb pemMapBox(const ProbeScene& scene, glm::vec3 centre) {
    Aabb box = Aabb::cube(centre, 0.5f * markupCellSize(scene.markup));
    for (ecs::Entity e : scene.loaded.entities)
        if (!scene.markup.mirrorEntities.contains(e))
            box.extend(meshWorldBounds(scene.registry, e));
    return box.translated(-centre);
}

PemAsset cookPemAsset(ProbeScene& scene, const PemCookSettings& s, const PemCookHooks& hooks) {
    validatePemCookSettings(s, scene.path);
    if (scene.markup.mirrorEntities.empty())
        throw Error(scene.path, "specula_reflector", "expected at least one reflector, found none");
    PemAsset asset;
    asset.centre = hooks.centre ? *hooks.centre
                                : markupProbeCentre(scene.registry, scene.markup, scene.loaded);
    asset.parameterKind = s.parameter;
    asset.path = s.path;
    asset.faceRes = s.faceRes;
    asset.skySource = scene.skyPath;
    asset.imageWidth = s.imageWidth;
    asset.imageHeight = s.imageHeight;
    const Aabb box = pemMapBox(scene, asset.centre);
    asset.boxMin = box.min;
    asset.boxMax = box.max;

    PemInferOptions infer;
    infer.faceRes = s.faceRes;
    infer.boxMin = box.min;
    infer.boxMax = box.max;
    infer.regularisation = s.regularisation;
    std::vector<glm::vec3> captured;
    if (s.geometry == "distance") {
        // The environment does not move with either parameter: one distance cube serves every
        // sample. d_inf past any real distance: every environment point lies in the box.
        const GroundTruthTracer environment(scene.registry, groundTruthOptions(scene, true));
        const float dInf = 2.5f * glm::length(box.max - box.min) + 1.f;
        asset.distance = std::make_shared<const PemDistanceGeometry>(bakePemDistanceGeometry(
            environment, asset.centre, s.faceRes, dInf, s.priorWeight > 0.f ? &captured : nullptr));
        asset.geometry = "distance";
        infer.distance = asset.distance;
        if (s.priorWeight > 0.f) {
            infer.prior = &captured;
            infer.priorWeight = s.priorWeight;
        }
    }
    PemSampleOptions so;
    so.supersample = s.supersample;
    // Hull flags in each reflector's own space: the same wherever the parameter moves it.
    std::unordered_map<ecs::Entity, PemHullFlags> hull;
    so.layers = s.localLayer != "off";
    if (so.layers)
        for (ecs::Entity e : scene.markup.mirrorEntities)
            if (const Mesh* mesh = scene.registry.find<Mesh>(e))
                hull.emplace(e, pemHullFlags(*mesh));
    so.hull = &hull;
    PemParameterState state(scene, s);
    auto traceAt = [&](float t) {
        const PemParameterState::At at = state.at(t);
        return tracePemSamples(*at.tracer, at.camera, asset.centre, so, scene.path);
    };
    if (hooks.fits) hooks.fits->clear();
    // The inference's share of the bar; the off-manifold measurement traces once more.
    const double share = hooks.fits ? 0.5 : 1.0;
    // Every sample traced first: "auto" decides on the local layer from all of them.
    std::vector<PemSamples> traced;
    for (int k = 0; k < s.samples; ++k) {
        if (hooks.cancelled && hooks.cancelled())
            throw Error(scene.path, "cancelled", "the bake was cancelled");
        const float t = float(k) / float(s.samples);
        try {
            traced.push_back(traceAt(t));
        } catch (const Error& e) {
            // Say which sample: a reflector walking out of the frame sees no pixel at one t.
            if (e.field() != "camera") throw;
            throw Error(e.file(), "camera",
                        "parameter sample " + std::to_string(k) + " (t = " + std::to_string(t) +
                            "): no reflector pixel to infer its map from (" + e.message() + ")");
        }
        if (hooks.progress) hooks.progress(share * 0.5 * double(k + 1) / double(s.samples));
    }
    bool local = s.localLayer == "on";
    if (s.localLayer == "auto")
        for (const PemSamples& samples : traced)
            local = local || pemCoverage(samples).selfHits > 0;
    PemInferOptions localInfer = infer;
    if (local) {
        asset.localLayer = true;
        asset.localFaceRes = s.localFaceRes > 0 ? s.localFaceRes : s.faceRes;
        asset.localSphere = localSphereOf(traced, s.localSphere == "fit");
        localInfer.faceRes = asset.localFaceRes;
    }
    for (int k = 0; k < s.samples; ++k) {
        if (hooks.cancelled && hooks.cancelled())
            throw Error(scene.path, "cancelled", "the bake was cancelled");
        const float t = float(k) / float(s.samples);
        const PemSamples& samples = traced[std::size_t(k)];
        PemSampleMap m;
        m.parameter = t;
        PemSampleFit fit;
        if (local) {
            PemLayers layers = inferPemLayers(samples, infer, localInfer, asset.localSphere);
            fit.unseenTexels = layers.distant.unseenTexels;
            fit.inferSeconds = layers.seconds;
            m.map = std::move(layers.distant.map);
            m.local = std::move(layers.local.map);
        } else {
            // No ray sees its own reflector: the distant target is the full one.
            PemInference inferred = inferPemMap(samples, infer);
            fit.unseenTexels = inferred.unseenTexels;
            fit.inferSeconds = inferred.seconds;
            m.map = std::move(inferred.map);
        }
        if (hooks.fits) {
            fit.parameter = t;
            fit.rays = int(samples.size());
            fit.localLayer = local;
            fit.selfHitFraction = pemCoverage(samples).fraction();
            fit.psnrOn = pemSamplesPsnr(
                samples, [&](const PemSample& p) { return sampleRadiance(m, local, p); });
            hooks.fits->push_back(fit);
        }
        asset.samples.push_back(std::move(m));
        if (hooks.progress) hooks.progress(share * (0.5 + 0.5 * double(k + 1) / double(s.samples)));
    }
    traced.clear();
    if (hooks.fits) measureOffManifold(asset, s, hooks, scene.path, traceAt);
    return asset;
}

} // namespace specula
