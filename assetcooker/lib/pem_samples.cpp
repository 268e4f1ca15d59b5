#include "pem_samples.h"

#include "engine/core/error.h"
#include "engine/scene/mesh_bounds.h"

#include <algorithm>
#include <cmath>

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
    if (s.parameter != "viewpoint")
        throw Error(file, "parameter",
                    "'" + s.parameter + "' is not implemented yet (only viewpoint is)");
    if (s.path != "orbit")
        throw Error(file, "path", "'" + s.path + "' is not implemented yet (only orbit is)");
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
    const Aabb box = pemMapBox(scene, asset.centre);
    asset.boxMin = box.min;
    asset.boxMax = box.max;

    const GroundTruthTracer tracer(scene.registry, groundTruthOptions(scene, false));
    PemInferOptions infer;
    infer.faceRes = s.faceRes;
    infer.boxMin = box.min;
    infer.boxMax = box.max;
    infer.regularisation = s.regularisation;
    PemSampleOptions so;
    so.supersample = s.supersample;
    for (int k = 0; k < s.samples; ++k) {
        if (hooks.cancelled && hooks.cancelled())
            throw Error(scene.path, "cancelled", "the bake was cancelled");
        const float t = float(k) / float(s.samples);
        const CameraView camera = walkOrbitCameraView(scene, s.imageWidth, s.imageHeight, t);
        const PemSamples samples = tracePemSamples(tracer, camera, asset.centre, so, scene.path);
        PemSampleMap m;
        m.parameter = t;
        m.map = inferPemMap(samples, infer).map;
        asset.samples.push_back(std::move(m));
        if (hooks.progress) hooks.progress(double(k + 1) / double(s.samples));
    }
    return asset;
}

} // namespace specula
