// Reflector pixels of a distance-cubemap probe. Permutation defines (0 or 1): HAS_ENVMAP,
// HAS_BOXPROJ, HAS_BISECTION, HAS_SECANT, HAS_AVGDIST, HAS_LAYERS, HAS_GLOSSY, HAS_FRESNEL,
// HAS_ROUGHNESS_MAP, and OUTPUT (0 colour, 1 probe-local position, 2 reflected direction, 3
// |n.v| in red, 4 TEXCOORD_0 in red and green: inputs for the CPU twin). HAS_GLOSSY (a rough
// reflector) reads the composite's prefiltered chain at the hit (distance_glossy_lookup.glsl.h)
// instead of the composite, times the GGX directional albedo E(|n.v|, roughness) (the chain is
// normalised; the microfacet surface returns E of it, engine/image/ggx_albedo.glsl.h), at the
// pixel's roughness: uRoughness times the roughness map at the pixel's TEXCOORD_0 with
// HAS_ROUGHNESS_MAP (reflector_roughness.glsl.h), uRoughness alone without.
#include "engine/core/glsl_device.glsl"
#include "engine/math/cube_face.glsl.h"
#include "engine/math/shading.glsl.h"
#include "components/reflection_probe/shaders/reflector_common.glsl.h"

#include "components/reflection_probe/distance/shaders/distance_lookup_types.glsl.h"
#include "components/reflection_probe/distance/shaders/distance_probe_gpu.glsl"

uniform sampler2D uSky;
uniform int uHasSky;
uniform vec3 uEye;
uniform float uF0;

in vec3 vWorldPos;
in vec3 vNormal;
in vec2 vUv;
out vec4 fragColor;

vec3 fetchSky(vec3 dir) {
    return uHasSky != 0 ? textureLod(uSky, equirectUv(dir), 0.0).rgb : vec3(0.0);
}

#include "components/reflection_probe/distance/shaders/distance_lookup.glsl.h"

#if HAS_GLOSSY
uniform float uRoughness; // perceptual factor, > 0 (alpha = roughness^2)
uniform int uChainLevels; // the chain's levels, the composite (level 0) included
#include "components/reflection_probe/shaders/reflector_roughness.glsl.h"
#include "components/reflection_probe/distance/shaders/distance_glossy_gpu.glsl"
#include "engine/math/cube_chain_sample.glsl.h"
#include "components/reflection_probe/distance/shaders/distance_glossy_lookup.glsl.h"
uniform sampler2D uGgxAlbedo;
float fetchGgxAlbedo(int i, int j) { return texelFetch(uGgxAlbedo, ivec2(i, j), 0).r; }
#include "engine/image/ggx_albedo.glsl.h"
#endif

void main() {
    // Probe-local space: the lookup never sees world coordinates.
    vec3 x = vWorldPos - probeCentre();
    vec3 v = normalize(vWorldPos - uEye);
    vec3 geometric = normalize(cross(dFdx(vWorldPos), dFdy(vWorldPos)));
    vec3 n = safeNormal(vNormal, geometric);
    vec3 lhat = normalize(mirrorDirection(v, n));

    DistanceParams p = lookupParams();
    int fetches = 0;
#if HAS_GLOSSY
    float roughness = reflectorRoughness(uRoughness, vUv);
    GlossySample glossy = probeGlossySample(x, lhat, roughness, p, uChainLevels);
    fetches += glossy.fetches;
    vec3 colour = glossy.radiance * ggxAlbedo(abs(dot(n, v)), roughness);
#else
    vec3 colour = probeRadiance(x, lhat, p, fetches);
#endif
#if HAS_FRESNEL
    colour *= schlickFresnel(uF0, abs(dot(n, v)));
#endif
#if OUTPUT == 1
    fragColor = vec4(x, 1.0);
#elif OUTPUT == 2
    fragColor = vec4(lhat, 1.0);
#elif OUTPUT == 3
    fragColor = vec4(abs(dot(n, v)), 0.0, 0.0, 1.0);
#elif OUTPUT == 4
    fragColor = vec4(vUv, 0.0, 1.0);
#else
    fragColor = vec4(colour, 1.0);
#endif
}
