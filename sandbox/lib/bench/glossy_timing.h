#pragma once
// The cost side of specula-sandbox glossy (glossy_bench.h): the GPU reflector pass of every
// glossy method that has a shader, per roughness, as a ratio to the classic environment
// map's mirror pass timed in the same run; and the texture memory each method holds.
//
// GPU paths: envmap+chain, boxproj+chain and rectified (footprint level) are the distance
// shader's HAS_GLOSSY path with the envmap, boxproj and secant methods
// (shaders/distance_glossy_lookup.glsl.h); light field glossy is the light-field shader's
// GLOSSY path. rectified (roughness level) exists on the CPU only: it has no pass time.
#include "assetcooker/lib/scene/scene_markup.h"
#include "components/reflection_probe/distance/distance_probe.h"
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "components/reflection_probe/lightfield/lightfield_asset.h"
#include "engine/image/ggx_prefilter.h"
#include "engine/math/camera.h"

#include <cstddef>
#include <string>
#include <vector>

namespace specula {
class ReflectionScene;
}

namespace specula::sandbox {

// Index of a glossyBenchMethods() name, in that order.
enum class GlossyBenchMethod {
    EnvmapChain,
    BoxprojChain,
    RectifiedRoughnessLevel,
    RectifiedFootprint,
    LayeredFootprint,
    LightField
};

// Whether the method has a shader (a pass to time).
bool hasGpuPath(GlossyBenchMethod method);

// The layered row's settings: every object layer searched by `search`'s method, the nearest
// layer's hit read in the composite's chain (shaders/distance_glossy_lookup.glsl.h).
DistanceProbe layeredSearch(const DistanceProbe& search);

// The textures the method's probe holds on the GPU at roughness `roughness`, in bytes, as
// the stores count them: the distance probe's composite cube (RGBA32F, one layer) and its sky,
// plus the object layers' tiles for the layered lookup (distance_store.h's storedLayerTiles),
// plus at roughness > 0 the GGX chain's levels past the composite (layered mode reads the
// composite's chain at the nearest layer's hit); the light field's atlas, plus at roughness
// > 0 its mips. Rough rows add the GGX albedo table (R32F, shared by every rough reflector of
// a store) and the reflectors' roughness maps (R32F, one texture per distinct map in each
// store whose rough reflectors read it: flavour_store_base.h's RoughnessMapTextures).
struct GlossyTextures {
    std::size_t cube = 0, sky = 0, chain = 0, layers = 0; // distance probe
    std::size_t atlas = 0, mips = 0;                      // light field
    std::size_t albedoTable = 0;
    std::size_t roughnessMaps = 0; // the markup's distinct roughness maps, 4 bytes a texel

    std::size_t bytes(GlossyBenchMethod method, float roughness) const;
};
GlossyTextures glossyTextures(const DistanceProbeAsset& distance, const CubeChain& chain,
                              const LightFieldAsset& lightField, const SceneMarkup& markup);

struct GlossyPassTime {
    float roughness = 0.f;
    GlossyBenchMethod method = GlossyBenchMethod::EnvmapChain;
    double ms = 0, ratioToEnvmap = 0; // median; its ratio to the mirror envmap pass
    int frames = 0;                   // timed frames the median rests on
};

struct GlossyTiming {
    double envmapMs = 0;                // the classic environment map (mirror, direction only)
    std::vector<GlossyPassTime> passes; // per roughness, the methods with a GPU path
    std::string timer;                  // what clock measured them
    std::size_t storeBytes = 0;         // the probe stores' own count after the runs
    std::size_t expectedStoreBytes = 0; // the same from GlossyTextures (a check)
};

// Times the reflector pass from `camera` for every roughness and GPU method, against the
// mirror envmap pass, in `rounds` interleaved rounds (one frame of every configuration a
// round, so a change of load on the machine falls on all alike; the frame after a switch is
// drawn untimed). Every method gets its own probe entity on the same cooked asset, so a switch
// changes only which probe the reflectors point at and their roughness. Needs a current GL
// context. `search`: the rectifying method (secant) and d_e.
GlossyTiming timeGlossyPasses(ReflectionScene& scene, const std::string& distanceManifest,
                              const std::string& lightFieldManifest, const DistanceProbe& search,
                              const CameraView& camera, const std::vector<float>& roughness,
                              const GlossyTextures& textures, int rounds = 15);

} // namespace specula::sandbox
