// Reflector pixels of a level of distance probes: up to LEVEL_K probes blended per pixel
// (distance_level_blend.glsl.h). Permutation defines (0 or 1): HAS_ENVMAP, HAS_BOXPROJ,
// HAS_BISECTION, HAS_SECANT (the one method every probe runs; HAS_AVGDIST and HAS_LAYERS
// are 0: each probe looks up its composite), HAS_FRESNEL; LEVEL_K (probes
// per pixel), LEVEL_BLEND (kLevelBlend*), and OUTPUT (0 colour, 1 world position, 2 reflected
// direction: the CPU twin's inputs).
#include "engine/core/glsl_device.glsl"
#include "engine/math/cube_face.glsl.h"
#include "engine/scene/shading.glsl.h"
#include "components/reflection_probe/shaders/reflector_common.glsl.h"

#include "components/reflection_probe/distance/shaders/distance_lookup_types.glsl.h"
#include "components/reflection_probe/distance/shaders/distance_level_gpu.glsl"

uniform sampler2D uSky;
uniform int uHasSky;
uniform vec3 uEye;
uniform float uF0;

in vec3 vWorldPos;
in vec3 vNormal;
out vec4 fragColor;

vec3 fetchSky(vec3 dir) {
    return uHasSky != 0 ? textureLod(uSky, equirectUv(dir), 0.0).rgb : vec3(0.0);
}

#include "components/reflection_probe/distance/shaders/distance_lookup.glsl.h"
#include "components/reflection_probe/distance/shaders/distance_seen.glsl.h"

vec3 levelRadiance(int probe, vec3 p, vec3 lhat, inout int fetches) {
    gProbe = probe;
    DistanceParams q = uLevel.probes[probe].lookup;
    return probeRadiance(p - q.centre, lhat, q, fetches);
}

SeenSample levelSeen(int probe, vec3 p, vec3 lhat) {
    gProbe = probe;
    DistanceParams q = uLevel.probes[probe].lookup;
    return probeSampleSeen(p - q.centre, lhat, q);
}

#include "components/reflection_probe/distance/shaders/distance_level_blend.glsl.h"

void main() {
    vec3 v = normalize(vWorldPos - uEye);
    vec3 geometric = normalize(cross(dFdx(vWorldPos), dFdy(vWorldPos)));
    vec3 n = safeNormal(vNormal, geometric);
    vec3 lhat = normalize(mirrorDirection(v, n));

    LevelBlendSample s = blendLevel(vWorldPos, lhat, LEVEL_BLEND, LEVEL_K);
    vec3 colour = s.radiance;
#if HAS_FRESNEL
    colour *= schlickFresnel(uF0, abs(dot(n, v)));
#endif
#if OUTPUT == 1
    fragColor = vec4(vWorldPos, 1.0);
#elif OUTPUT == 2
    fragColor = vec4(lhat, 1.0);
#else
    fragColor = vec4(colour, 1.0);
#endif
}
