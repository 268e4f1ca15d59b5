#include "assetcooker/lib/flavours/pem/pem_samples.h"

#include "components/reflection_probe/walk_path.h"
#include "engine/core/error.h"
#include "engine/raytrace/triangle_plane.h"

#include <algorithm>
#include <cmath>
#include <limits>
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

} // namespace

namespace {

// The layered fields of one reflector ray leaving `hit` from `origin` (PemSampleOptions::layers).
void traceLayers(const GroundTruthTracer& tracer, const Hit& hit, glm::vec3 origin,
                 const PemSampleOptions& o, PemSample& s) {
    const ecs::Entity self = hit.entity;
    const auto again = tracer.fullScene().intersect(origin, s.l);
    s.selfHit = again && again->entity == self;
    s.distant = s.target;
    if (s.selfHit) {
        // Through the reflector: the first thing past it, traced from just before that point
        // (the tracer then resolves it, reflecting on any other mirror as the full truth does).
        const EmbreeScene::Filter notSelf = [self](ecs::Entity e) { return e != self; };
        const auto beyond = tracer.fullScene().intersect(
            origin, s.l, 1e-4f, std::numeric_limits<float>::infinity(), &notSelf);
        if (!beyond) {
            s.distant = tracer.sky(s.l);
        } else {
            const float m = std::max({std::fabs(beyond->position.x), std::fabs(beyond->position.y),
                                      std::fabs(beyond->position.z), 1.f});
            s.distant = tracer.radiance(beyond->position - 1e-3f * m * s.l, s.l, 1);
        }
    }
    s.onHull = true;
    if (o.hull) {
        const auto it = o.hull->find(self);
        if (it != o.hull->end() && hit.primitiveIndex < it->second.firstTriangle.size())
            s.onHull = it->second.flag(hit.primitiveIndex, hit.triangle);
    }
}

// The reflected direction as tracePemSamples computes it for the primary ray `dir`.
glm::vec3 mirrorOf(const Hit& hit, glm::vec3 dir) {
    const glm::vec3 n = glm::dot(hit.normal, dir) > 0.f ? -hit.normal : hit.normal;
    return glm::normalize(glm::reflect(dir, n));
}

// GLSL's dFdxFine / dFdyFine of x and l at sub-pixel (px, py) of `fine` (ReflectorQuadPixel's
// quads: columns (2i, 2i + 1), window rows counted from the bottom), the partners on the
// plane of `hit`'s triangle, times `scale` sub-pixels per displayed pixel.
void fillFootprint(const ecs::Registry& registry, const CameraView& fine, int px, int py,
                   const Hit& hit, glm::vec3 centre, float scale, PemSample& s) {
    auto partner = [&](int x, int y, glm::vec3& xOut, glm::vec3& lOut) {
        glm::vec3 origin, dir;
        fine.primaryRay(x, y, origin, dir);
        const std::optional<Hit> h = hitOnTrianglePlane(registry, hit, origin, dir);
        // Parallel to the plane: the pixel itself, a zero derivative (as the quad twin).
        xOut = h ? h->position - centre : s.x;
        lOut = h ? mirrorOf(*h, dir) : s.l;
    };
    glm::vec3 xp, lp;
    partner(px ^ 1, py, xp, lp);
    const float sx = (px & 1) ? -scale : scale; // an odd column is the quad's right pixel
    s.dxdX = sx * (xp - s.x);
    s.dldX = sx * (lp - s.l);
    const int row = fine.height - 1 - py; // window row
    partner(px, fine.height - 1 - (row ^ 1), xp, lp);
    const float sy = (row & 1) ? -scale : scale;
    s.dxdY = sy * (xp - s.x);
    s.dldY = sy * (lp - s.l);
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
                    const int ss = o.supersample;
                    s.pixel = (y / ss) * camera.width + x / ss;
                    s.centre = ss % 2 == 1 && x % ss == ss / 2 && y % ss == ss / 2;
                    s.x = hit->position - probeCentre;
                    s.l = glm::normalize(glm::reflect(dir, n));
                    const glm::vec3 origin2 = offsetAlong(hit->position, ng);
                    s.target = tracer.radiance(origin2, s.l, 1);
                    if (o.layers) traceLayers(tracer, *hit, origin2, o, s);
                    // The centre ray is the displayed pixel's own: its quad is the
                    // rasteriser's, one displayed pixel apart.
                    if (o.registry && s.centre)
                        fillFootprint(*o.registry, camera, x / ss, y / ss, *hit, probeCentre, 1.f,
                                      s);
                    else if (o.registry)
                        fillFootprint(*o.registry, fine, x, y, *hit, probeCentre, float(ss), s);
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
    PemSampleOptions withRegistry = o;
    if (!withRegistry.registry) withRegistry.registry = &scene.registry;
    return tracePemSamples(tracer, camera, probeCentre, withRegistry, scene.path);
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
    if (!(s.roundingReach >= 0.f && s.roundingReach <= 0.01f))
        throw Error(file, "rounding_reach", "expected 0 to 0.01 (metres; radians)");
    if (s.localLayer != "auto" && s.localLayer != "on" && s.localLayer != "off")
        throw Error(file, "local_layer", "expected auto, on or off, got '" + s.localLayer + "'");
    if (s.localFaceRes != 0) requireRange(file, "local_face_res", s.localFaceRes, 1, 1024);
    requireRange(file, "mip_levels", s.mipLevels, 1, PemMap::maxLevels(s.faceRes));
    if (s.localSphere != "bound" && s.localSphere != "fit")
        throw Error(file, "local_sphere", "expected bound or fit, got '" + s.localSphere + "'");
    if (s.rows != "pixel" && s.rows != "centre" && s.rows != "subray")
        throw Error(file, "rows", "expected pixel, centre or subray, got '" + s.rows + "'");
    if (s.rows == "centre" && s.supersample % 2 == 0)
        throw Error(file, "rows",
                    "'centre' needs a sub-ray through each pixel's centre: an odd supersample, "
                    "got " +
                        std::to_string(s.supersample));
    if (s.compression != "none" && s.compression != "bc6h")
        throw Error(file, "compression", "expected none or bc6h, got '" + s.compression + "'");
    if (s.parameter != "viewpoint" && s.parameter != "reflector")
        throw Error(file, "parameter",
                    "expected viewpoint or reflector, got '" + s.parameter + "'");
    WalkPath path;
    if (s.parameter == "viewpoint" && s.path == kCameraPathName) return;
    if (s.parameter == "viewpoint" && s.path != "orbit")
        throw Error(file, "path",
                    "the viewpoint moves along the walk's camera orbit ('orbit') or the scene "
                    "camera's animation ('camera'), got '" +
                        s.path + "'");
    if (s.path == kCameraPathName)
        throw Error(file, "path",
                    "'camera' moves the viewpoint (--parameter viewpoint); the reflectors walk "
                    "orbit, line or figure8");
    if (!parseWalkPath(s.path, path))
        throw Error(file, "path", "expected orbit, line or figure8, got '" + s.path + "'");
}

double pemSamplesPsnr(const PemSamples& samples,
                      const std::function<glm::vec3(const PemSample&)>& radiance, PemRows rows) {
    const std::vector<std::vector<int>> dataRows = pemDataRows(samples, rows);
    const double rms = pemRowsRms(samples, dataRows, rows, radiance);
    // Nothing measured (no ray), or a black target met by black maps (a sky-only scene
    // without a sky agrees with any black bake): no PSNR, as compareImages has it.
    const bool signal =
        std::ranges::any_of(samples, [](const PemSample& p) { return p.target != glm::vec3(0.f); });
    if (dataRows.empty() || (rms == 0.0 && !signal))
        return std::numeric_limits<double>::quiet_NaN();
    return 10.0 * std::log10(1.0 / std::max(rms * rms, 1e-12));
}

bool pemPathClosed(const PemCookSettings& s) {
    return s.path != kCameraPathName;
}

float pemSampleParameter(const PemCookSettings& s, int k) {
    if (pemPathClosed(s)) return float(k) / float(s.samples);
    return s.samples > 1 ? float(k) / float(s.samples - 1) : 0.f;
}

PemRows pemRows(const PemCookSettings& s) {
    return s.rows == "subray"   ? PemRows::SubRay
           : s.rows == "centre" ? PemRows::Centre
                                : PemRows::Pixel;
}

} // namespace specula
