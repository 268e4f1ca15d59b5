#pragma once
// What a rasteriser interpolates where a triangle does not reach: the fragment shader's
// derivatives (dFdx, dFdy, the MIP level of a texture read) subtract values of the 2 x 2
// pixel quad, and a quad partner the triangle does not cover is still shaded, as a helper
// invocation, with the triangle's own attributes extrapolated over its plane. A CPU twin of
// anything a shader differentiates needs those values, and hitOnTrianglePlane gives them.
#include "engine/ecs/registry.h"
#include "engine/raytrace/embree_scene.h"

#include <optional>

namespace specula {

// Where the ray origin + t dir meets the plane of `on`'s triangle (any t, even behind the
// origin, as the rasteriser's interpolation does not care), with barycentric weights that may
// leave [0, 1] and the normal interpolated with them exactly as EmbreeScene interpolates it on
// the triangle (world-space vertex normals by the normal matrix, normalised; the geometric
// normal where unusable). `on` must come from an EmbreeScene of this registry, unchanged since.
// Empty when the ray runs parallel to the plane or the triangle is degenerate. Fills t,
// position, entity, primitive, primitiveIndex, triangle, barycentric, geometricNormal, normal.
std::optional<Hit> hitOnTrianglePlane(const ecs::Registry& registry, const Hit& on,
                                      glm::vec3 origin, glm::vec3 dir);

} // namespace specula
