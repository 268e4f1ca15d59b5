#include "pem_samples.h"

#include "assetcooker/lib/pem_geometry.h"
#include "components/reflection_probe/pem/pem_blend.h"
#include "components/reflection_probe/walk_path.h"
#include "engine/core/error.h"
#include "engine/scene/mesh_bounds.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace specula {

namespace {

// Off the surface before the reflected ray leaves, relative to the coordinates' size (as the
// tracer offsets its own secondary rays).
glm::vec3 offsetAlong(glm::vec3 p, glm::vec3 n) {
    const float m = std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z), 1.f});
    return p + 1e-4f * m * n;
}

void requireRange(const std::string& file, const char* field, int v, int lo, int hi) {
    if (v < lo || v > hi)
        throw Error(file, field,
                    "expected " + std::to_string(lo) + " to " + std::to_string(hi) + ", got " +
                        std::to_string(v));
}

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
        const PemLookupCpu a(asset.samples[std::size_t(w.a)].map);
        const PemLookupCpu b(asset.samples[std::size_t(w.b)].map);
        (*hooks.fits)[std::size_t(k)].psnrOff = pemSamplesPsnr(trace(t), [&](const PemSample& p) {
            return glm::mix(a.radiance(p.x, p.l), b.radiance(p.x, p.l), w.wb);
        });
        if (hooks.progress) hooks.progress(0.5 + 0.5 * double(k + 1) / double(s.samples));
    }
}

} // namespace

PemSamples tracePemSamples(const GroundTruthTracer& tracer, const CameraView& camera,
                           glm::vec3 probeCentre, const PemSampleOptions& o,
                           const std::string& file) {
    requireRange(file, "supersample", o.supersample, 1, 16);
    const TraceOptions& t = tracer.options();
    if (t.mirrors.empty())
        throw Error(file, "specula_reflector", "expected at least one reflector, found none");
    if (t.environmentOnly != o.environmentOnly)
        throw Error(file, "environment_only", "expected a tracer with the same environmentOnly");
    // The sub-pixel centres are the pixel centres of the same view at supersample x the size.
    CameraView fine = camera;
    fine.width = camera.width * o.supersample;
    fine.height = camera.height * o.supersample;
    std::vector<PemSamples> rows(std::size_t(std::max(fine.height, 0)));
    tbb::parallel_for(
        tbb::blocked_range<int>(0, fine.height), [&](const tbb::blocked_range<int>& r) {
            for (int y = r.begin(); y != r.end(); ++y)
                for (int x = 0; x < fine.width; ++x) {
                    glm::vec3 origin, dir;
                    fine.primaryRay(x, y, origin, dir);
                    const std::optional<Hit> hit = tracer.fullScene().intersect(origin, dir);
                    if (!hit || !t.mirrors.contains(hit->entity)) continue;
                    // The mirror direction as GroundTruthTracer::resolve reflects: about the
                    // shading normal turned to the viewer, leaving off the geometric normal's side.
                    const glm::vec3 n =
                        glm::dot(hit->normal, dir) > 0.f ? -hit->normal : hit->normal;
                    const glm::vec3 ng = glm::dot(hit->geometricNormal, dir) > 0.f
                                             ? -hit->geometricNormal
                                             : hit->geometricNormal;
                    PemSample s;
                    s.x = hit->position - probeCentre;
                    s.l = glm::normalize(glm::reflect(dir, n));
                    s.target = tracer.radiance(offsetAlong(hit->position, ng), s.l, 1);
                    rows[std::size_t(y)].push_back(s);
                }
        });
    PemSamples out;
    for (const PemSamples& row : rows)
        out.insert(out.end(), row.begin(), row.end());
    if (out.empty())
        throw Error(file, "camera",
                    "expected a camera that sees a reflector; no pixel of " +
                        std::to_string(camera.width) + " x " + std::to_string(camera.height) +
                        " hits one");
    return out;
}

PemSamples tracePemSamples(ProbeScene& scene, const CameraView& camera, glm::vec3 probeCentre,
                           const PemSampleOptions& o) {
    if (scene.markup.mirrorEntities.empty())
        throw Error(scene.path, "specula_reflector", "expected at least one reflector, found none");
    const GroundTruthTracer tracer(scene.registry, groundTruthOptions(scene, o.environmentOnly));
    return tracePemSamples(tracer, camera, probeCentre, o, scene.path);
}

void validatePemCookSettings(const PemCookSettings& s, const std::string& file) {
    requireRange(file, "samples", s.samples, 1, kMaxPemSamples);
    requireRange(file, "face_res", s.faceRes, 1, 1024);
    requireRange(file, "supersample", s.supersample, 1, 16);
    if (!(s.regularisation >= 0.f) || !std::isfinite(s.regularisation))
        throw Error(file, "regularisation", "expected a finite lambda >= 0");
    if (s.imageWidth < 1 || s.imageHeight < 1 || s.imageWidth > 4096 || s.imageHeight > 4096)
        throw Error(file, "image_size", "expected 1 to 4096 pixels on each side");
    if (s.geometry != "box" && s.geometry != "distance")
        throw Error(file, "geometry", "expected box or distance, got '" + s.geometry + "'");
    if (!(s.priorWeight >= 0.f) || !std::isfinite(s.priorWeight))
        throw Error(file, "prior_weight", "expected a finite weight >= 0");
    if (s.priorWeight > 0.f && s.geometry != "distance")
        throw Error(file, "prior_weight",
                    "the prior is the radiance the distance geometry captures: needs geometry "
                    "distance");
    if (s.parameter != "viewpoint" && s.parameter != "reflector")
        throw Error(file, "parameter",
                    "expected viewpoint or reflector, got '" + s.parameter + "'");
    if (s.path == "camera")
        throw Error(file, "path",
                    "'camera' needs the glTF camera's animation, which the loader does not read "
                    "yet (use orbit, or line/figure8 with --parameter reflector)");
    WalkPath path;
    if (s.parameter == "viewpoint" && s.path != "orbit")
        throw Error(file, "path",
                    "the viewpoint moves along the walk's camera orbit only ('orbit'), got '" +
                        s.path + "'");
    if (!parseWalkPath(s.path, path))
        throw Error(file, "path", "expected orbit, line or figure8, got '" + s.path + "'");
}

double pemSamplesPsnr(const PemSamples& samples,
                      const std::function<glm::vec3(const PemSample&)>& radiance) {
    double sum = 0;
    for (const PemSample& p : samples) {
        const glm::dvec3 d = glm::dvec3(radiance(p)) - glm::dvec3(p.target);
        sum += glm::dot(d, d);
    }
    const double mse = samples.empty() ? 0.0 : sum / (3.0 * double(samples.size()));
    return 10.0 * std::log10(1.0 / std::max(mse, 1e-12));
}

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
    PemParameterState state(scene, s);
    auto traceAt = [&](float t) {
        const PemParameterState::At at = state.at(t);
        return tracePemSamples(*at.tracer, at.camera, asset.centre, so, scene.path);
    };
    if (hooks.fits) hooks.fits->clear();
    for (int k = 0; k < s.samples; ++k) {
        if (hooks.cancelled && hooks.cancelled())
            throw Error(scene.path, "cancelled", "the bake was cancelled");
        const float t = float(k) / float(s.samples);
        PemSamples samples;
        try {
            samples = traceAt(t);
        } catch (const Error& e) {
            // Say which sample: a reflector walking out of the frame sees no pixel at one t.
            if (e.field() != "camera") throw;
            throw Error(e.file(), "camera",
                        "parameter sample " + std::to_string(k) + " (t = " + std::to_string(t) +
                            "): no reflector pixel to infer its map from (" + e.message() + ")");
        }
        PemInference inferred = inferPemMap(samples, infer);
        if (hooks.fits) {
            PemSampleFit fit;
            fit.parameter = t;
            fit.rays = int(samples.size());
            fit.unseenTexels = inferred.unseenTexels;
            fit.inferSeconds = inferred.seconds;
            const PemLookupCpu lookup(inferred.map);
            fit.psnrOn = pemSamplesPsnr(
                samples, [&](const PemSample& p) { return lookup.radiance(p.x, p.l); });
            hooks.fits->push_back(fit);
        }
        PemSampleMap m;
        m.parameter = t;
        m.map = std::move(inferred.map);
        asset.samples.push_back(std::move(m));
        // The off-manifold measurement traces once more per sample: its share of the bar.
        const double share = hooks.fits ? 0.5 : 1.0;
        if (hooks.progress) hooks.progress(share * double(k + 1) / double(s.samples));
    }
    if (hooks.fits) measureOffManifold(asset, s, hooks, scene.path, traceAt);
    return asset;
}

} // namespace specula
