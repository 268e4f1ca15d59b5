// Reflector pixels of a light-field-slab probe (and, with BACKGROUND=1, the environment seen
// from an eye inside the slabs). Permutation defines: HAS_FRESNEL (0/1), BACKGROUND (0/1),
// GLOSSY (0/1: a rough reflector, shaders/lightfield_glossy.glsl.h over the atlas's mips, times
// the GGX albedo E), HAS_ROUGHNESS_MAP (0/1: with GLOSSY, the roughness is uRoughness times
// the roughness map at the pixel's TEXCOORD_0, reflector_roughness.glsl.h), OUTPUT (0 colour,
// 1 cell-local position, 2 lookup direction, 3 shading normal, 4 TEXCOORD_0 in red and green:
// inputs for the CPU twin).
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
uniform vec3 uEye;
uniform float uF0;
#if BACKGROUND
uniform mat4 uInvViewProj;
uniform vec2 uViewport;
#else
in vec3 vWorldPos;
in vec3 vNormal;
in vec2 vUv;
#endif
out vec4 fragColor;

vec3 fetchAtlas(int slab, vec2 texel) {
    return textureLod(uAtlas, vec3(texel / uAtlasSize, float(slab)), 0.0).rgb;
}

float slabDisparity(int slab) { return uDisparity[slab]; }

#include "components/reflection_probe/lightfield/shaders/lightfield_lookup.glsl.h"

#if GLOSSY
uniform float uRoughness;     // perceptual factor, > 0
#include "components/reflection_probe/shaders/reflector_roughness.glsl.h"
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

void main() {
    LightFieldParams prm;
    prm.halfCell = uHalfCell;
    prm.cameras = uCameras;
    prm.res = uRes;
#if BACKGROUND
    // The eye ray through this pixel, from the eye: the light field is the environment as
    // seen from anywhere in the cell.
    vec2 ndc = gl_FragCoord.xy / uViewport * 2.0 - 1.0;
    vec4 farP = uInvViewProj * vec4(ndc, 1.0, 1.0);
    vec3 x = uEye - uCellCentre;
    vec3 lhat = normalize(farP.xyz / farP.w - uEye);
    vec3 colour = lightFieldRadiance(x, lhat, prm);
#else
    // Cell-local space: the lookup never sees world coordinates.
    vec3 x = vWorldPos - uCellCentre;
    vec3 v = normalize(vWorldPos - uEye);
    vec3 geometric = normalize(cross(dFdx(vWorldPos), dFdy(vWorldPos)));
    vec3 n = safeNormal(vNormal, geometric);
    vec3 lhat = normalize(mirrorDirection(v, n));
#if GLOSSY
    LightFieldGlossy g;
    g.roughness = reflectorRoughness(uRoughness, vUv);
    g.rays = uGlossyRays;
    g.raysPerTexel = uRaysPerTexel;
    g.levelBias = uLevelBias;
    g.maxLevel = uMaxLevel;
    vec3 colour = lightFieldGlossyRadiance(x, lhat, n, g, prm) *
                  ggxAlbedo(lightFieldAlbedoCosine(n, lhat), min(g.roughness, 1.0));
#else
    vec3 colour = lightFieldRadiance(x, lhat, prm);
#endif
#if HAS_FRESNEL
    colour *= schlickFresnel(uF0, abs(dot(n, v)));
#endif
#endif
#if OUTPUT == 1
    fragColor = vec4(x, 1.0);
#elif OUTPUT == 2
    fragColor = vec4(lhat, 1.0);
#elif OUTPUT == 3 && !BACKGROUND
    fragColor = vec4(n, 1.0);
#elif OUTPUT == 4 && !BACKGROUND
    fragColor = vec4(vUv, 0.0, 1.0);
#else
    fragColor = vec4(colour, 1.0);
#endif
}
