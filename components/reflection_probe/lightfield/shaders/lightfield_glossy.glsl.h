// Shared by GLSL and C++ (see engine/core/glsl_host.h): the glossy lookup of a light-field-slab
// probe (issue 14), the shader's GLOSSY path and the CPU twin's glossyRadiance. Include it
// after lightfield_lookup.glsl.h; the includer also provides
//   vec3 fetchAtlasLevel(int slab, vec2 texel, int level)   bilinear RGB of mip `level` of
//        layer `slab` (lightfield_mips.h), `texel` in level-0 texel units as for fetchAtlas
//        (the same normalised coordinate at every level), clamped to the layer
//
// What a rough reflector shows at p is the GGX lobe about its mirror direction,
//     L(p, v) = E(n.v) * sum_l w(l) L(p, l) / sum_l w(l),
// a normalised filter times the directional albedo E (engine/image/ggx_albedo.h; the caller
// multiplies, the filter here is normalised so a uniform light field reads back exactly).
// A light field holds every ray through the cell, so the lobe can be gathered in two ways:
//  - a wider aperture: average the lookups of several rays of the lobe, each with its own
//    parallax (its own slab, camera-plane intersection and four cameras). Exact in shape and
//    parallax, but a handful of rays leaves a handful of sharp copies;
//  - mips of the camera images: a camera image blurred by an angle is what that camera sees
//    through a cone. The rays of a cone of slope width w from p hit the focal plane (at z_f
//    beyond the camera plane; p lies `along` before it) over (along + z_f) w, which a camera
//    on the plane sees over (along + z_f) w / z_f: the blur a camera needs is the lobe's
//    width times F = 1 + along / z_f. Exact at the focal plane, and wherever along = 0.
// Here both: K rays of the lobe, each read with the quadrilinear lookup at the mip level that
// covers that ray's share of the lobe. The rays carry what a blur cannot: GGX's long tail, the
// lobe's stretch and tilt at grazing view, a lobe that spans cameras or slabs; the mips fill
// the space between the rays (no sharp copy of an edge or a texture shows) and average what
// level 0, a point sample per texel, aliases. K's cap, its rule's factor and the level bias:
// lightfield_probe_cpu.h, with the measurements. Roughness 0 is the mirror lookup itself, bit
// for bit.
//
// The rays: a fixed pattern of visible normals (Heitz 2018, "Sampling the GGX Distribution of
// Visible Normals"), l = reflect(-v, h), the same at every pixel of one K (no noise):
// K = 1 is the centre of the visible-normal disk (nearly the mirror direction: all blur from
// the mips); an even K takes point pairs (r, phi), (r, phi + pi) of a Vogel spiral,
// r = sqrt((j + 1/2) / (K/2)), phi = j * golden angle: equal areas of the disk, and symmetric
// through its centre, so the frame's flip where the view crosses the normal changes nothing.
// Each ray weighs w = G2(v, l) / G1(v) (Smith height-correlated; 0 below the horizon), the
// estimator's weight, and stands for the solid angle Omega = 1 / (K pdf(l)),
// pdf(l) = G1(v) D(h) / (4 n.v). On the slab that ray reads, Omega covers
//     A = Omega / |l_a|^3 * F^2 * (RES / 2)^2      texels of level 0
// (|l_a|: the direction's slab-axis component; dslope^2 = dOmega / |l_a|^3; RES / 2 texels
// per unit slope), with 1 / z_f from the slab's disparity (disparity = spacing RES / (2 z_f),
// spacing = 6 h / (NUM - 1)): F = 1 + along * disparity * (NUM - 1) / (3 h RES). The level
// whose texel has that area: lod = log2(A) / 2 + levelBias, clamped to [0, maxLevel], read
// trilinearly (the two levels around lod, each clamped to the camera's tile at that level).
// The bias the shader uses, log2(2 / sqrt(12)) = -0.79, gives the level's trilinear kernel
// (a 2^k box, then the bilinear tent: standard deviation 2^k / 2 texels) the standard
// deviation of the ray's square share (side / sqrt(12)).
// K per pixel, from the lobe's footprint (lightFieldLobeRays): the mips blur each ray's share
// exactly only at the focal plane, so rays are needed where the lobe spans what a blur cannot
// stand for (parallax across cameras and slabs, GGX's tail, the grazing stretch), and a lobe
// that covers a texel or less is the mirror lookup already. The footprint is the lobe's solid
// angle Omega_lobe = 1 / pdf at its peak (h = n) = 4 pi alpha^2 n.v (1 + Lambda(n.v)), on the
// slab of the mirror ray read as A above (level-0 texels, the magnification F included); then
//     K = the least power of two >= raysPerTexel * sqrt(A), at most `rays` (1 for a lobe under
// half a texel wide). Omega_lobe grows with the roughness and the mirror ray's coordinates do
// not depend on it, so K never falls as the roughness rises. K grows with the lobe's width, not
// its area: on the room (tests/probe/lightfield_glossy_rays_test.cpp, both capped at 32) K = the
// least power of two >= A lost 0.04 dB against K = 16 at r = 0.1 for 50 fetches a pixel where
// this rule lost 0.02 for 43, and took 207 fetches at r = 0.2 where this rule took 149.
// raysPerTexel = 2 is the least of 1.5, 2, 3 within 0.05 dB of K = 16 at every roughness there
// (1.5 lost 0.07). The cap (`rays`): lightfield_probe_cpu.h. The pattern of each K is fixed,
// so the image is deterministic; where K changes between neighbouring pixels the colour steps
// 0.0010-0.0024 more than the fixed-K image's at the same pixels (steps of 0.016-0.18 there),
// as much as the rule adds where K does not change (0-0.0014): no seam shows.
// Cost: per ray 4 bilinear fetches at an integral level, else 8: at most 8 K per pixel.
#ifndef SPECULA_LIGHTFIELD_GLOSSY_GLSL_H
#define SPECULA_LIGHTFIELD_GLOSSY_GLSL_H

struct LightFieldGlossy {
    float roughness;    // perceptual (alpha = roughness^2), clamped to 1; <= 0 or NaN: a mirror
    int rays;           // the most rays K a pixel takes: 1 or even
    float raysPerTexel; // the footprint rule's factor; <= 0 or NaN: K = rays at every pixel
    float levelBias;    // added to every ray's mip level
    int maxLevel;       // the atlas's deepest mip level (0: no mips, the rays alone)
};

// Smith's Lambda of GGX at cosine c (> 0) to the normal, a2 = alpha^2.
float lightFieldLambda(float c, float a2) {
    float c2 = c * c;
    return 0.5f * (sqrt(1.0f + a2 * (1.0f - c2) / c2) - 1.0f);
}

// Point i of the K-point pattern on the unit disk (see the header comment).
vec2 lightFieldLobeDisk(int i, int rays) {
    if (rays <= 1) return vec2(0.0f);
    int pairs = (rays + 1) / 2;
    int j = i / 2;
    float r = sqrt((float(j) + 0.5f) / float(pairs));
    float phi = float(j) * 2.39996323f + ((i & 1) != 0 ? 3.14159265f : 0.0f);
    return r * vec2(cos(phi), sin(phi));
}

// One camera's tile at mip `level`, the pixel clamped to the texel centres of that level in
// the tile (level-0 pixel units: 2^level / 2 - 1/2 .. RES - 2^level / 2 - 1/2), so filtering
// never reads a neighbouring camera; at level 0 the mirror lookup's clamp.
vec3 lightFieldTileFetch(int slab, vec2 camIndex, vec2 px, int level, LightFieldParams prm) {
    float margin = 0.5f * float(1 << level);
    px = clamp(px, vec2(margin - 0.5f), vec2(float(prm.res) - margin - 0.5f));
    return fetchAtlasLevel(slab, camIndex * float(prm.res) + px + 0.5f, level);
}

// The quadrilinear lookup of lightFieldRadiance at mip level lod (>= 0): per camera, levels
// floor(lod) and floor(lod) + 1 blended. 4 bilinear fetches at an integral level, else 8.
vec3 lightFieldSlabsAtLevel(SlabCoords sc, float lod, int maxLevel, LightFieldParams prm) {
    float last = float(prm.cameras - 1);
    vec2 cam = clamp(sc.camera, vec2(0.0f), vec2(last));
    vec2 base = min(floor(cam), vec2(last - 1.0f));
    vec2 f = cam - base;
    float disparity = slabDisparity(sc.slab);
    int level0 = min(int(lod), maxLevel);
    int level1 = min(level0 + 1, maxLevel);
    float fl = lod - float(level0);
    vec3 sum = vec3(0.0f);
    for (int k = 0; k < 4; ++k) {
        vec2 corner = vec2(float(k & 1), float(k >> 1));
        vec2 camIndex = base + corner;
        vec2 px = sc.pixel + (cam - camIndex) * disparity;
        vec3 c = lightFieldTileFetch(sc.slab, camIndex, px, level0, prm);
        if (fl > 0.0f && level1 > level0)
            c = mix(c, lightFieldTileFetch(sc.slab, camIndex, px, level1, prm), fl);
        vec2 w2 = mix(vec2(1.0f) - f, f, corner);
        sum += (w2.x * w2.y) * c;
    }
    return sum;
}

// The level-0 texels that `omega` steradians about the ray `l` (unit) cover on the slab it
// reads through slab coordinates sc (A of the header comment).
float lightFieldTexelArea(SlabCoords sc, vec3 l, float omega, LightFieldParams prm) {
    float axial = max(abs(l[sc.slab / 2]), 0.5f); // >= 1/sqrt(3) for the slab's own axis
    float disparity = max(slabDisparity(sc.slab), 0.0f);
    float magnify = 1.0f + max(sc.along, 0.0f) * disparity * float(prm.cameras - 1) /
                               (3.0f * prm.halfCell * float(prm.res));
    float texelsPerSlope = 0.5f * float(prm.res) * magnify;
    return omega / (axial * axial * axial) * texelsPerSlope * texelsPerSlope;
}

// The mip level for a ray `l` (unit) of the lobe standing for `omega` steradians.
float lightFieldRayLevel(SlabCoords sc, vec3 l, float omega, LightFieldGlossy g,
                         LightFieldParams prm) {
    float lod = 0.5f * log2(max(lightFieldTexelArea(sc, l, omega, prm), 1e-30f)) + g.levelBias;
    return clamp(lod, 0.0f, float(g.maxLevel));
}

// K at a pixel: the footprint rule (see the header comment), the lobe of roughness
// g.roughness (> 0) about the mirror direction lhat (unit) at p, nv its clamped n.v.
int lightFieldLobeRays(vec3 p, vec3 lhat, float nv, LightFieldGlossy g, LightFieldParams prm) {
    if (!(g.raysPerTexel > 0.0f)) return g.rays;
    float r = min(g.roughness, 1.0f);
    float alpha = max(r * r, 1e-6f);
    float a2 = alpha * alpha;
    float omega = 4.0f * 3.14159265f * a2 * nv * (1.0f + lightFieldLambda(nv, a2));
    float area = lightFieldTexelArea(slabCoords(p, lhat, prm), lhat, omega, prm);
    float want = g.raysPerTexel * sqrt(area);
    int k = 1;
    while (k < g.rays && float(k) < want)
        k *= 2;
    return min(k, g.rays);
}

// The n.v that E(n.v, roughness) is read at: |n.lhat| (= |n.v|), kept above 1e-4 as the
// ground truth keeps n.v.
float lightFieldAlbedoCosine(vec3 n, vec3 lhat) {
    return clamp(abs(dot(n, lhat)), 1e-4f, 1.0f);
}

// The normalised GGX filter of the light field at p (cell-local) for a reflector of normal n
// (either orientation; the side lhat leaves is used) and mirror direction lhat (unit).
// Roughness <= 0 or NaN: lightFieldRadiance(p, lhat) itself.
vec3 lightFieldGlossyRadiance(vec3 p, vec3 lhat, vec3 n, LightFieldGlossy g,
                              LightFieldParams prm) {
    if (!(g.roughness > 0.0f)) return lightFieldRadiance(p, lhat, prm);
    float r = min(g.roughness, 1.0f);
    float alpha = max(r * r, 1e-6f);
    float a2 = alpha * alpha;
    vec3 nf = dot(n, lhat) >= 0.0f ? n : -n;
    float cosine = dot(nf, lhat);
    // The view (towards the eye) is the mirror direction reflected back; n.v is kept above
    // 1e-4 as the ground truth keeps it.
    vec3 wo = 2.0f * cosine * nf - lhat;
    float nv = clamp(cosine, 1e-4f, 1.0f);
    // Frame (tangent, bitangent, nf) with the view in the tangent-normal plane; at normal
    // incidence any tangent (Duff et al. 2017), the pattern being symmetric through its centre.
    vec3 tangent = wo - cosine * nf;
    float t2len = dot(tangent, tangent);
    if (!(t2len > 1e-12f)) {
        float s = nf.z >= 0.0f ? 1.0f : -1.0f;
        float q = -1.0f / (s + nf.z);
        tangent = vec3(1.0f + s * nf.x * nf.x * q, s * nf.x * nf.y * q, -s * nf.x);
        t2len = dot(tangent, tangent);
    }
    tangent *= inversesqrt(t2len);
    vec3 bitangent = cross(nf, tangent);
    // Heitz 2018 in the local frame, where the view has no bitangent component: the view
    // stretched to roughness 1 (vh), the disk's axes t1 (the bitangent) and t2, and the
    // warp of the disk onto the visible hemisphere's projection (s).
    vec3 ve = vec3(sqrt(1.0f - nv * nv), 0.0f, nv);
    vec3 vh = normalize(vec3(alpha * ve.x, 0.0f, ve.z));
    vec3 t1 = vec3(0.0f, 1.0f, 0.0f);
    vec3 t2 = cross(vh, t1);
    float s = 0.5f * (1.0f + vh.z);
    float lambdaV = lightFieldLambda(nv, a2);
    int rays = lightFieldLobeRays(p, lhat, nv, g, prm);
    vec3 sum = vec3(0.0f);
    float weights = 0.0f;
    for (int i = 0; i < rays; ++i) {
        vec2 u = lightFieldLobeDisk(i, rays);
        float u2 = (1.0f - s) * sqrt(max(1.0f - u.x * u.x, 0.0f)) + s * u.y;
        vec3 nh = u.x * t1 + u2 * t2 + sqrt(max(1.0f - u.x * u.x - u2 * u2, 0.0f)) * vh;
        vec3 h = normalize(vec3(alpha * nh.x, alpha * nh.y, max(nh.z, 0.0f)));
        vec3 l = 2.0f * dot(ve, h) * h - ve;
        if (!(l.z > 0.0f)) continue; // below the horizon: weight 0
        float w = (1.0f + lambdaV) / (1.0f + lambdaV + lightFieldLambda(l.z, a2));
        float q = h.z * h.z * (a2 - 1.0f) + 1.0f;
        float pdf = a2 / (3.14159265f * q * q) / ((1.0f + lambdaV) * 4.0f * nv);
        vec3 dir = normalize(l.x * tangent + l.y * bitangent + l.z * nf);
        SlabCoords sc = slabCoords(p, dir, prm);
        float lod = lightFieldRayLevel(sc, dir, 1.0f / (float(rays) * pdf), g, prm);
        sum += w * lightFieldSlabsAtLevel(sc, lod, g.maxLevel, prm);
        weights += w;
    }
    return weights > 0.0f ? sum / weights : lightFieldRadiance(p, lhat, prm);
}

#endif
