#include "engine/raytrace/ground_truth.h"
#include "engine/scene/shading.h"

#include "engine/core/glsl_host.h"
#include "engine/image/sampling.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace specula {

namespace {

// Pushes a secondary ray's origin off the surface it starts on, relative to the size of the
// coordinates so large worlds do not re-hit their own surface.
float offsetEpsilon(glm::vec3 p) {
    const float m = std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z), 1.f});
    return 1e-4f * m;
}

} // namespace

GroundTruthTracer::GroundTruthTracer(ecs::Registry& registry, TraceOptions options)
    : options_(std::move(options)),
      environment_(registry, [this](ecs::Entity e) { return !options_.mirrors.contains(e); }),
      full_(registry) {}

glm::vec3 GroundTruthTracer::sky(glm::vec3 dir) const {
    if (!options_.sky || options_.sky->empty()) return glm::vec3(0.f);
    const glm::vec3 d = glm::normalize(dir);
    return glm::vec3(sampleBilinear(*options_.sky, glsl::equirectUv(d), Wrap::Repeat, Wrap::Clamp));
}

glm::vec3 GroundTruthTracer::shade(const Hit& hit) const {
    return glsl::shadeSurface(hit.albedo, hit.normal);
}

glm::vec3 GroundTruthTracer::radiance(glm::vec3 origin, glm::vec3 dir, int depth) const {
    const EmbreeScene& scene = (options_.environmentOnly && depth > 0) ? environment_ : full_;
    return resolve(scene.intersect(origin, dir), dir, depth);
}

glm::vec3 GroundTruthTracer::resolve(const std::optional<Hit>& hit, glm::vec3 dir,
                                     int depth) const {
    if (!hit) return sky(dir);
    if (!options_.mirrors.contains(hit->entity)) return shade(*hit);
    if (depth >= options_.maxBounces) return glm::vec3(0.f);

    const glm::vec3 d = glm::normalize(dir);
    // Mirror about the shading normal, as the rasteriser does, turned towards the viewer so
    // a back-facing mirror still reflects.
    const glm::vec3 n = glm::dot(hit->normal, d) > 0.f ? -hit->normal : hit->normal;
    const glm::vec3 ng =
        glm::dot(hit->geometricNormal, d) > 0.f ? -hit->geometricNormal : hit->geometricNormal;
    const glm::vec3 r = glm::reflect(d, n);
    const glm::vec3 next = hit->position + offsetEpsilon(hit->position) * ng;
    glm::vec3 tint(1.f);
    if (options_.mirrorTint) tint = options_.mirrorTint(hit->entity);
    return tint * radiance(next, r, depth + 1);
}

EnvSample GroundTruthTracer::traceEnvironment(glm::vec3 origin, glm::vec3 dir,
                                              const std::function<bool(ecs::Entity)>* only) const {
    EnvSample s;
    const glm::vec3 d = glm::normalize(dir);
    const std::optional<Hit> hit =
        environment_.intersect(origin, d, 1e-4f, std::numeric_limits<float>::infinity(), only);
    if (!hit) {
        s.radiance = sky(d);
        return s;
    }
    s.hit = true;
    s.distance = hit->t;
    s.entity = hit->entity;
    s.radiance = shade(*hit);
    return s;
}

GroundTruthImage GroundTruthTracer::render(const CameraView& camera) const {
    GroundTruthImage out;
    out.color = Image(camera.width, camera.height, 3);
    out.mirrorMask = Image(camera.width, camera.height, 1);
    out.depth = Image(camera.width, camera.height, 1);
    const glm::vec3 eye = camera.eye();
    tbb::parallel_for(tbb::blocked_range<int>(0, camera.height),
                      [&](const tbb::blocked_range<int>& rows) {
                          for (int y = rows.begin(); y != rows.end(); ++y) {
                              for (int x = 0; x < camera.width; ++x) {
                                  glm::vec3 origin, dir;
                                  camera.primaryRay(x, y, origin, dir);
                                  const std::optional<Hit> hit = full_.intersect(origin, dir);
                                  const glm::vec3 c = resolve(hit, dir, 0);
                                  float mask = 0.f;
                                  float depth = std::numeric_limits<float>::infinity();
                                  if (hit) {
                                      depth = glm::length(hit->position - eye);
                                      if (options_.mirrors.contains(hit->entity)) mask = 1.f;
                                  }
                                  float* p = out.color.at(x, y);
                                  p[0] = c.r;
                                  p[1] = c.g;
                                  p[2] = c.b;
                                  out.mirrorMask.at(x, y)[0] = mask;
                                  out.depth.at(x, y)[0] = depth;
                              }
                          }
                      });
    return out;
}

} // namespace specula
