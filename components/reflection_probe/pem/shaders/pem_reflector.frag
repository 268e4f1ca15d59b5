// Reflector pixels of a parameterized-environment-map probe: speculaReflect of the host library
// (pem_host.glsl: the lookup of the two samples the parameter block names, mixed by its
// weight), the local layer over it, times Fresnel. Defines: GEOMETRY_DISTANCE (0 the box
// lookup, pem_lookup.glsl.h; 1 the distance-rectified one, pem_distance_lookup.glsl.h),
// HAS_FRESNEL (0/1), PEM_MIP (0/1: the distant maps have MIP levels, read trilinear at the
// level the pixel's footprint picks, pem_lod.glsl.h), HAS_LOCAL_LAYER (0/1: the local layer over
// the distant one, off the reflector's hull; pem_local_lookup.glsl.h), OUTPUT (0 colour, 1
// probe-local position, 2 reflected direction, 3 the hull flag in red, 4 the MIP level of
// detail in red, 0 without PEM_MIP: inputs for the CPU twin).
#include "components/reflection_probe/pem/shaders/pem_host.glsl"

#if HAS_LOCAL_LAYER
// Premultiplied RGB and coverage per texel, layered as uPemMaps.
uniform sampler2DArray uPemLocal;
// One bit per triangle of the drawn reflector, all its primitives in order (pem_hull.h); this
// draw's first triangle is bit uPemHullBase (gl_PrimitiveID restarts at each draw).
layout(std430, binding = kPemHullBinding) readonly buffer PemHullFlags {
    uint uPemHullBits[];
};
uniform int uPemHullBase;
#endif
uniform vec3 uEye;
uniform float uF0;

in vec3 vWorldPos;
in vec3 vNormal;
out vec4 fragColor;

#if HAS_LOCAL_LAYER
// The two samples blended texel by texel, as fetchTexel does the distant maps.
vec4 fetchLocalTexel(int face, int i, int j) {
    vec4 a = texelFetch(uPemLocal, ivec3(i, j, uPem.layerA + face), 0);
    if (uPem.wb <= 0.0) return a;
    return mix(a, texelFetch(uPemLocal, ivec3(i, j, uPem.layerB + face), 0), uPem.wb);
}

#include "components/reflection_probe/pem/shaders/pem_local_lookup.glsl.h"

bool onHull() {
    int k = uPemHullBase + gl_PrimitiveID;
    return ((uPemHullBits[k >> 5] >> uint(k & 31)) & 1u) != 0u;
}
#endif

void main() {
    vec3 v = normalize(vWorldPos - uEye);
    vec3 colour = speculaReflect(vWorldPos, vNormal, v, 0.0);
    // The twin's inputs, as speculaReflect derives them.
    vec3 x = vWorldPos - uPem.centre;
    vec3 n = safeNormal(vNormal, normalize(cross(dFdx(vWorldPos), dFdy(vWorldPos))));
    vec3 lhat = normalize(mirrorDirection(v, n));
    float hull = 1.0;
#if HAS_LOCAL_LAYER
    // Hull triangles never see the reflector: the distant layer alone (alpha 0).
    if (!onHull()) {
        hull = 0.0;
        colour = pemComposite(
            pemLocalRadiance(x, lhat, uPem.localCentre, uPem.localRadius, uPem.localFaceRes),
            colour);
    }
#endif
#if HAS_FRESNEL
    colour *= schlickFresnel(uF0, abs(dot(n, v)));
#endif
#if OUTPUT == 1
    fragColor = vec4(x, 1.0);
#elif OUTPUT == 2
    fragColor = vec4(lhat, 1.0);
#elif OUTPUT == 3
    fragColor = vec4(hull, 0.0, 0.0, 1.0);
#elif OUTPUT == 4
#if PEM_MIP
    fragColor = vec4(gPemLod, 0.0, 0.0, 1.0);
#else
    fragColor = vec4(0.0, 0.0, 0.0, 1.0);
#endif
#else
    fragColor = vec4(colour, 1.0);
#endif
}
