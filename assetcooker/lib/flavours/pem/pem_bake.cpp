#include "assetcooker/lib/flavours/pem/pem_bake.h"
#include "assetcooker/lib/scene/walk_amplitude.h"

#include "assetcooker/lib/flavours/pem/pem_geometry.h"
#include "assetcooker/lib/flavours/pem/pem_layers.h"
#include "components/reflection_probe/walk_path.h"
#include "engine/core/error.h"

namespace specula {

// The scene at parameter t: parameter "viewpoint" moves the camera along the walk's orbit
// (walkOrbitCameraView) or the scene camera's animation (path "camera", cameraPathView) past
// reflectors that stay put, so one tracer serves every t;
// parameter "reflector" moves the reflectors along the walk path (walkOffset) before a fixed
// camera (the orbit's t = 0, the scene camera), so each t gets a tracer of the moved scene.
// The reflectors are back where the scene authors them when the state goes.
class PemBake::State {
public:
    struct At {
        const GroundTruthTracer* tracer;
        CameraView camera;
    };

    State(ProbeScene& scene, const PemCookSettings& s)
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
    ~State() {
        if (byReflector_) roots_.setOffset(scene_.registry, glm::vec3(0.f));
    }
    State(const State&) = delete;
    State& operator=(const State&) = delete;

    At at(float t) {
        if (!byReflector_ && s_.path == kCameraPathName)
            return {&*tracer_, cameraPathView(scene_, s_.imageWidth, s_.imageHeight, t)};
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

bool pemLocalDecisionNeedsTraces(const PemCookSettings& s) {
    return s.localLayer != "off";
}

PemDecisionInputs pemDecisionInputs(const PemSamples& samples) {
    PemDecisionInputs in;
    in.selfHits = pemCoverage(samples).selfHits > 0;
    for (const PemSample& p : samples)
        if (!p.onHull) in.offHull.push_back(p.x);
    return in;
}

PemLocalDecision decidePemLocalLayer(const PemCookSettings& s,
                                     const std::vector<PemDecisionInputs>& inputs,
                                     const std::function<std::vector<glm::vec3>()>& allPoints) {
    PemLocalDecision d;
    d.local = s.localLayer == "on";
    if (s.localLayer == "auto")
        for (const PemDecisionInputs& in : inputs)
            d.local = d.local || in.selfHits;
    if (!d.local) return d;
    d.faceRes = s.localFaceRes > 0 ? s.localFaceRes : s.faceRes;
    std::vector<glm::vec3> points;
    for (const PemDecisionInputs& in : inputs)
        points.insert(points.end(), in.offHull.begin(), in.offHull.end());
    // With no point off the hull an "on" layer only ever reads alpha 0.
    if (points.empty())
        d.sphere = boundPemLocalSphere(allPoints());
    else
        d.sphere = s.localSphere == "fit" ? fitPemLocalSphere(points) : boundPemLocalSphere(points);
    return d;
}

PemLocalDecision decidePemLocalLayer(const PemCookSettings& s,
                                     const std::vector<PemSamples>& traced) {
    std::vector<PemDecisionInputs> inputs;
    for (const PemSamples& samples : traced)
        inputs.push_back(pemDecisionInputs(samples));
    return decidePemLocalLayer(s, inputs, [&] {
        std::vector<glm::vec3> all;
        for (const PemSamples& samples : traced)
            for (const PemSample& p : samples)
                all.push_back(p.x);
        return all;
    });
}

PemBake::PemBake(ProbeScene& scene, const PemCookSettings& s, std::optional<glm::vec3> centre,
                 Needs needs)
    : scene_(scene), s_(s) {
    validatePemCookSettings(s, scene.path);
    if (scene.markup.mirrorEntities.empty())
        throw Error(scene.path, "specula_reflector", "expected at least one reflector, found none");
    // Before any tracing (the distance cube below too): a camera path the scene does not have
    // is refused at once.
    if (s.path == kCameraPathName) cameraPathView(scene, s.imageWidth, s.imageHeight, 0.f);
    asset_.centre =
        centre ? *centre : markupProbeCentre(scene.registry, scene.markup, scene.loaded);
    asset_.parameterKind = s.parameter;
    asset_.path = s.path;
    asset_.faceRes = s.faceRes;
    asset_.mipLevels = s.mipLevels;
    asset_.skySource = scene.skyPath;
    asset_.imageWidth = s.imageWidth;
    asset_.imageHeight = s.imageHeight;
    const Aabb box = pemMapBox(scene, asset_.centre);
    asset_.boxMin = box.min;
    asset_.boxMax = box.max;

    infer_.faceRes = s.faceRes;
    infer_.mipLevels = s.mipLevels;
    infer_.boxMin = box.min;
    infer_.boxMax = box.max;
    infer_.regularisation = s.regularisation;
    infer_.rows = pemRows(s);
    infer_.nonNegative = s.nonNegative;
    infer_.roundingReach = s.roundingReach;
    if ((needs & Infer) && s.geometry == "distance") {
        // The environment does not move with either parameter: one distance cube serves every
        // sample. d_inf past any real distance: every environment point lies in the box.
        const GroundTruthTracer environment(scene.registry, groundTruthOptions(scene, true));
        const float dInf = 2.5f * glm::length(box.max - box.min) + 1.f;
        asset_.distance = std::make_shared<const PemDistanceGeometry>(
            bakePemDistanceGeometry(environment, asset_.centre, s.faceRes, dInf,
                                    s.priorWeight > 0.f ? &captured_ : nullptr));
        asset_.geometry = "distance";
        infer_.distance = asset_.distance;
        if (s.priorWeight > 0.f) {
            infer_.prior = &captured_;
            infer_.priorWeight = s.priorWeight;
        }
    }
    options_.supersample = s.supersample;
    options_.registry = &scene.registry; // the footprints' quad partners (PemSample::dxdX...)
    // Hull flags in each reflector's own space: the same wherever the parameter moves it.
    options_.layers = pemLocalDecisionNeedsTraces(s);
    if ((needs & Trace) && options_.layers)
        for (ecs::Entity e : scene.markup.mirrorEntities)
            if (const Mesh* mesh = scene.registry.find<Mesh>(e))
                hull_.emplace(e, pemHullFlags(*mesh));
    options_.hull = &hull_;
    if (needs & Trace) state_ = std::make_unique<State>(scene, s_);
}

PemBake::~PemBake() = default;

std::optional<PemSamples> PemBake::traceAt(float t) {
    const State::At at = state_->at(t);
    try {
        return tracePemSamples(*at.tracer, at.camera, asset_.centre, options_, scene_.path);
    } catch (const Error& e) {
        if (e.field() != "camera") throw;
        return std::nullopt;
    }
}

PemSamples PemBake::trace(int k) {
    const float t = parameter(k);
    try {
        const State::At at = state_->at(t);
        return tracePemSamples(*at.tracer, at.camera, asset_.centre, options_, scene_.path);
    } catch (const Error& e) {
        // Say which sample: a reflector walking out of the frame sees no pixel at one t.
        if (e.field() != "camera") throw;
        throw Error(e.file(), "camera",
                    "parameter sample " + std::to_string(k) + " (t = " + std::to_string(t) +
                        "): no reflector pixel to infer its map from (" + e.message() + ")");
    }
}

PemSampleMap PemBake::infer(int k, const PemSamples& samples, const PemLocalDecision& d,
                            PemSampleFit* fit) const {
    PemSampleMap m;
    m.parameter = parameter(k);
    PemSampleFit f;
    if (d.local) {
        PemInferOptions localInfer = infer_;
        localInfer.faceRes = d.faceRes;
        PemLayers layers = inferPemLayers(samples, infer_, localInfer, d.sphere);
        f.unseenTexels = layers.distant.unseenTexels;
        f.roundingRows = layers.distant.roundingRows;
        f.inferSeconds = layers.seconds;
        m.map = std::move(layers.distant.map);
        m.local = std::move(layers.local.map);
    } else {
        // No ray sees its own reflector: the distant target is the full one.
        PemInference inferred = inferPemMap(samples, infer_);
        f.unseenTexels = inferred.unseenTexels;
        f.roundingRows = inferred.roundingRows;
        f.inferSeconds = inferred.seconds;
        m.map = std::move(inferred.map);
    }
    if (fit) *fit = f;
    return m;
}

PemAsset PemBake::assemble(const PemLocalDecision& d, std::vector<PemSampleMap> samples) const {
    PemAsset asset = asset_;
    if (d.local) {
        asset.localLayer = true;
        asset.localFaceRes = d.faceRes;
        asset.localSphere = d.sphere;
    }
    asset.samples = std::move(samples);
    return asset;
}

} // namespace specula
