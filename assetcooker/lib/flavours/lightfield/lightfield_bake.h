#pragma once
// Bakes a light-field-slab probe with Embree (docs/design.md §5): six slabs of NUM x NUM cameras of
// RES x RES pixels around a cubic cell. Rays, not the rasteriser, because each camera sample
// is a line, and a line can be traced from where it leaves the cell instead of from the
// camera plane: a reflector anywhere in the cell then sees exactly what the sample recorded,
// even when geometry (a floor, a column) lies between the cell and the extended camera plane,
// where a rasterised camera would have it behind it or clipped. Lines that miss the cell
// start on the camera plane. The same tracer and shading as the ground truth, so the probe
// can be exact where the light field's sampling allows.
#include "assetcooker/lib/flavours/lightfield/lightfield_rows.h"
#include "assetcooker/lib/scene/scene_markup.h"
#include "components/reflection_probe/lightfield/lightfield_asset.h"
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
    // Precomputed blocks (traceLightFieldRows, e.g. a sharded bake's parts): when set, nothing
    // is traced and the probe is assembled from them. They must cover each slab's camera rows
    // 0 .. cameras - 1 exactly once, with this bake's cameras and res; else Error naming the
    // rows missing or overlapping. The result is byte-identical to the traced bake.
    const std::vector<LightFieldRows>* blocks = nullptr;
};

// Traces the probe (or assembles options.blocks) and finalises each slab: the depth range
// from the histogram's quantiles, the focal plane and disparity, BC1 if asked.
LightFieldAsset bakeLightFieldProbe(ecs::Registry& registry, const SceneMarkup& markup,
                                    const LightFieldBakeOptions& options);

// Traces one block: slab `slab` (0 .. 5), camera rows [j0, j1) (0 <= j0 < j1 <= cameras),
// the same rays and bytes as bakeLightFieldProbe gives those rows. The placement check runs
// as for the whole probe. options.blocks is ignored; options.progress gets the block's
// fraction done.
LightFieldRows traceLightFieldRows(ecs::Registry& registry, const SceneMarkup& markup,
                                   const LightFieldBakeOptions& options, int slab, int j0, int j1);

// Environment objects whose bounds reach into the cell or into a slab's region between the
// cell and its extended camera plane (docs/design.md §5), with how far (LightFieldIntrusion::depth:
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
