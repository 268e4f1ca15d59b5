#pragma once
// Bakes a light-field-slab probe with Embree (DESIGN §5): six slabs of NUM x NUM cameras of
// RES x RES pixels around a cubic cell. Rays, not the rasteriser, because each camera sample
// is a line, and a line can be traced from where it leaves the cell instead of from the
// camera plane: a reflector anywhere in the cell then sees exactly what the sample recorded,
// even when geometry (a floor, a column) lies between the cell and the extended camera plane,
// where a rasterised camera would have it behind it or clipped. Lines that miss the cell
// start on the camera plane. The same tracer and shading as the ground truth, so the probe
// can be exact where the light field's sampling allows.
#include "components/reflection_probe/lightfield/lightfield_asset.h"
#include "components/reflection_probe/scene_markup.h"
#include "engine/ecs/registry.h"
#include "engine/image/image.h"

#include <functional>
#include <string>
#include <vector>

namespace specula {

struct LightFieldBakeOptions {
    glm::vec3 cellCentre{0.f}; // world space
    float cellSize = 1.5f;     // l
    int cameras = 8;           // NUM per side
    int res = 64;              // RES
    LightFieldCompression compression = LightFieldCompression::None;
    // The focal plane comes from the depth range between this percentile and its mirror
    // (1 - p) of the samples (sky = +inf). The extremes would let the few samples that meet
    // the floor just beyond a side slab's plane pull the focal plane to it and blur the
    // walls, which most reflected rays see; 0.4 keeps the focal plane on the walls.
    float depthPercentile = 0.4f;
    const Image* sky = nullptr;           // equirectangular; black when null
    std::function<void(double)> progress; // fraction done, from the baking threads
    std::function<bool()> cancelled;      // polled per camera; true aborts with Error
    // Where the cell centre's placement warnings go (checkProbePlacement); null: dropped.
    std::vector<std::string>* warnings = nullptr;
};

LightFieldAsset bakeLightFieldProbe(ecs::Registry& registry, const SceneMarkup& markup,
                                    const LightFieldBakeOptions& options);

// Environment objects whose bounds reach into the cell or into a slab's region between the
// cell and its extended camera plane (DESIGN §5), with how far (LightFieldIntrusion::depth:
// how deep inside the cell the bounds reach; negative: the gap to the cell).
std::vector<LightFieldIntrusion> findLightFieldIntrusions(const SceneMarkup& markup,
                                                          glm::vec3 cellCentre, float cellSize);

struct ReflectorOverhang {
    std::string node;
    float metres = 0.f; // how far the reflector's bounds reach outside the cell
};
// Reflectors whose bounds are not inside the cell (the light field is exact only inside).
std::vector<ReflectorOverhang> findReflectorOverhangs(const ecs::Registry& registry,
                                                      const SceneMarkup& markup,
                                                      glm::vec3 cellCentre, float cellSize);

} // namespace specula
