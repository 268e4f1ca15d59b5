// The light-field flavour's entry point for a host's own fragment shader (LightFieldHostProbe,
// lightfield_host_probe.h): the host prepends LightFieldHostProbe::glslLibrary() (this file
// with its includes expanded, after the GLOSSY define) and calls
//     vec3 speculaReflect(vec3 worldPos, vec3 normal, vec3 viewDir, float roughness)
// worldPos: the reflector point in world space (exact inside the probe's cell); normal: its
// shading normal (any length; a zero or NaN normal falls back to the screen-space geometric
// one); viewDir: from the eye to the point; roughness: perceptual. Returns the radiance the
// reflector reflects, before the host's Fresnel and albedo: with GLOSSY the GGX filter of the
// slabs (lightfield_glossy.glsl.h over the atlas's mips) times the directional albedo, at every
// roughness (0: the mirror lookup times E(n.v, 0)); without it the mirror lookup. Specula's own
// reflector pass (lightfield_reflector.frag) calls it too. LightFieldHostProbe::bindTo binds
// the atlas and sets the uniforms below on units the host chose.
#include "engine/core/glsl_device.glsl"
#include "components/reflection_probe/shaders/reflector_common.glsl.h"

// Layer k = slab k (+X -X +Y -Y +Z -Z), a (NUM RES)^2 atlas of camera tiles; see
// lightfield_asset.h.
uniform sampler2DArray uAtlas;
uniform float uAtlasSize;
uniform vec3 uCellCentre;
uniform float uHalfCell;
uniform int uCameras;
uniform int uRes;
uniform float uDisparity[6];

vec3 fetchAtlas(int slab, vec2 texel) {
    return textureLod(uAtlas, vec3(texel / uAtlasSize, float(slab)), 0.0).rgb;
}

float slabDisparity(int slab) { return uDisparity[slab]; }

#include "components/reflection_probe/lightfield/shaders/lightfield_lookup.glsl.h"

#if GLOSSY
uniform int uGlossyRays;      // the most rays K a pixel takes
uniform float uRaysPerTexel;  // the footprint rule's factor (0: K = uGlossyRays everywhere)
uniform float uLevelBias;     // added to each ray's mip level
uniform int uMaxLevel;        // the atlas's deepest mip level
uniform sampler2D uGgxAlbedo; // kGgxAlbedoSize^2 R32F: E(n.v = i / 31, roughness = j / 31)

// The same normalised coordinate at every level (mips of lightfield_mips.h; the atlas is
// mipmapped with GL_LINEAR_MIPMAP_NEAREST, so an integral lod reads that level bilinearly).
vec3 fetchAtlasLevel(int slab, vec2 texel, int level) {
    return textureLod(uAtlas, vec3(texel / uAtlasSize, float(slab)), float(level)).rgb;
}

float fetchGgxAlbedo(int i, int j) { return texelFetch(uGgxAlbedo, ivec2(i, j), 0).r; }

#include "engine/image/ggx_albedo.glsl.h"
#include "components/reflection_probe/lightfield/shaders/lightfield_glossy.glsl.h"
#endif

LightFieldParams lightFieldParams() {
    LightFieldParams prm;
    prm.halfCell = uHalfCell;
    prm.cameras = uCameras;
    prm.res = uRes;
    return prm;
}

vec3 speculaReflect(vec3 worldPos, vec3 normal, vec3 viewDir, float roughness) {
    // Cell-local space: the lookup never sees world coordinates.
    vec3 x = worldPos - uCellCentre;
    vec3 v = normalize(viewDir);
    vec3 geometric = normalize(cross(dFdx(worldPos), dFdy(worldPos)));
    vec3 n = safeNormal(normal, geometric);
    vec3 lhat = normalize(mirrorDirection(v, n));
    LightFieldParams prm = lightFieldParams();
#if GLOSSY
    LightFieldGlossy g;
    g.roughness = roughness;
    g.rays = uGlossyRays;
    g.raysPerTexel = uRaysPerTexel;
    g.levelBias = uLevelBias;
    g.maxLevel = uMaxLevel;
    return lightFieldGlossyRadiance(x, lhat, n, g, prm) *
           ggxAlbedo(lightFieldAlbedoCosine(n, lhat), min(g.roughness, 1.0));
#else
    return lightFieldRadiance(x, lhat, prm);
#endif
}
