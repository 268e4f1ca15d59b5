// Shared by GLSL and C++ (see engine/core/glsl_host.h): which level of a probe's GGX
// prefiltered chain (engine/image/ggx_prefilter.h: level i prefiltered with perceptual
// roughness r_i = i / (levels - 1), alpha = r_i^2, N = V = R) a glossy reflection reads.
// Positions are probe-local (origin at the probe centre).
//
// Engines read the chain at the level of the reflector's roughness alone. That level's lobe
// is the blur seen from the probe centre, where the chain was made; a reflector elsewhere
// sees the same surface from another distance. The lobe leaves the reflector with angular
// half-width theta(alpha), so at the hit, t along the reflected ray, it covers a footprint
// of radius ~ t tan(theta); from the centre, |q| away, that footprint spans an angle
// ~ atan(t tan(theta) / |q|). The level whose own lobe has that half-width is the one to
// read: sharper where the reflector nearly touches what it reflects (t << |q|), blurrier
// where the hit lies farther from the reflector than from the centre (contact hardening).
//
// theta(alpha): the half-angle about the mirror direction of the cone that holds half of
// the lobe. GGX half-vectors h ~ D(h) (n.h) have the polar-angle CDF
//     P(theta_h <= a) = tan^2(a) / (alpha^2 + tan^2(a))
// (the inverse that GGX importance sampling uses, Walter et al. 2007), so half of them lie
// within tan(theta_h) = alpha; with N = V = R a half-vector at theta_h reflects the view
// to l at 2 theta_h from R, hence theta(alpha) = 2 atan(alpha) (~ 2 alpha for glossy
// lobes). The prefilter's (n.l) weight and the 1 / (4 v.h) Jacobian are left out: both
// are ~ 1 inside a glossy lobe. The share (one half) hardly matters: any share s gives
// tan(theta_h) = c alpha with c = sqrt(s / (1 - s)), and in the small-angle limit the
// mapping below is alpha_level = alpha t / |q| whatever c is.
//
// Approximations: N = V = R for both lobes (as the chain itself; a grazing lobe is longer
// and leans away from R); the footprint is taken on a plane across the ray, not on the hit
// surface: the surface's tilt stretches the footprint by 1 / cos of the ray's incidence
// angle, and the centre sees that stretch foreshortened by the cos of its own incidence
// angle, so the two cancel while x and the centre see the hit from similar directions
// (|x| small next to |q|); the footprint is treated as facing the centre (the same
// condition); the hit distance is the search's t, so a search that lands on the wrong
// surface picks the level of that surface.
#ifndef SPECULA_DISTANCE_GLOSSY_GLSL_H
#define SPECULA_DISTANCE_GLOSSY_GLSL_H

// The level engines read: perceptual roughness times (levels - 1), linear over the chain
// (ggxChainLevel in engine/image/ggx_prefilter.h). The envmap and boxproj lookups keep it:
// they stand for what engines do.
float glossyEngineLevel(float roughness, int levels) {
    return clamp(roughness, 0.0f, 1.0f) * float(levels - 1);
}

// theta(alpha) above: the half-width of the GGX lobe of alpha about the mirror direction.
float glossyLobeHalfAngle(float alpha) {
    return 2.0f * atan(alpha);
}

// The half-width of bilinear reconstruction on a cube face, in texels: a tent per axis is
// close to a Gaussian of sigma = texel / sqrt(6), whose half mass lies within 1.18 sigma.
const float kBilinearHalfWidthTexels = 0.48f;

// The blur of chain level i, as a half-width: level i >= 1 the lobe it was prefiltered with
// (r_i = i / (levels - 1), ggxChainRoughness in engine/image/ggx_prefilter.h); level 0, the
// composite itself, only its texels' (2 / n radians at a face's centre, n = its face size).
float glossyLevelHalfAngle(int level, int levels, int n) {
    if (level < 1) return kBilinearHalfWidthTexels * 2.0f / float(max(n, 1));
    float r = float(level) / float(max(levels - 1, 1));
    return glossyLobeHalfAngle(r * r);
}

// The fractional level that blurs by half-width theta. From level 1 on, the levels sample
// roughness (r_i = i / (levels - 1)) and a read between two of them goes linearly in the
// roughness whose lobe is theta wide, as engines read their chains. Below level 1 it goes
// linearly in the half-width, from level 0's texel blur to level 1's lobe: level 0 is no
// roughness at all (r = 0 is infinitely sharp; only its texels blur it), and read linearly
// in roughness there, r = 0.1 took half the sharp composite and half the r = 0.2 level (four
// times its lobe), and r = 0.05 a quarter of it: on the room 29.6 and 31.9 dB against 31.0
// and 34.5 read this way (glossy bench, 160 x 120, issue 14). Below level 0's blur, level 0.
float glossyHalfAngleLevel(float theta, int levels, int n) {
    if (levels < 2) return 0.0f;
    float sharp = glossyLevelHalfAngle(0, levels, n);
    float first = glossyLevelHalfAngle(1, levels, n);
    if (theta < first) return max(theta - sharp, 0.0f) / max(first - sharp, 1e-9f);
    // theta = 2 atan(r^2): r = sqrt(tan(theta / 2)), theta at most pi / 2 (alpha = 1).
    float r = sqrt(tan(0.5f * min(theta, 1.5707963f)));
    return clamp(r, 0.0f, 1.0f) * float(levels - 1);
}

// The chain level of a lobe of perceptual roughness `roughness` seen from the probe centre:
// the level whose blur is that lobe's (engines read r (levels - 1) instead). n: level 0's
// (the composite's) face size.
float glossyRoughnessLevel(float roughness, int levels, int n) {
    float r = clamp(roughness, 0.0f, 1.0f);
    return glossyHalfAngleLevel(glossyLobeHalfAngle(r * r), levels, n);
}

// The level whose blur, seen from the probe centre, covers what a lobe of this roughness
// leaving x along lhat covers at the hit t along the ray (q = x + t lhat). Wherever t = |q|
// (x at the centre, for one) it is glossyRoughnessLevel; a nearer hit reads a lower level, a
// farther one a higher level, and t <= 0 (the reflector touches the surface) level 0. For
// glossy lobes alpha_level ~ alpha t / |q|.
float glossyFootprintLevel(float roughness, vec3 x, vec3 lhat, float t, int levels, int n) {
    float r = clamp(roughness, 0.0f, 1.0f);
    float theta = glossyLobeHalfAngle(r * r);
    float ray = max(t, 0.0f);
    float fromCentre = max(length(x + ray * lhat), 1e-6f);
    // atan(t tan(theta) / |q|), written so theta = pi/2 (alpha = 1) stays finite; the second
    // argument stays > 0 (atan(0, 0) is undefined in GLSL, and cos(pi/2) rounds below 0).
    float phi = atan(ray * sin(theta), fromCentre * max(cos(theta), 1e-6f));
    return glossyHalfAngleLevel(phi, levels, n);
}

// Below level 1, the share of level 0 in a read, which is the mirror lookup's own answer
// rather than the chain's copy of the composite. Where a rough ray finds nothing, the mirror
// reads the sky panorama; the composite holds the sky only at its face resolution, so a
// near-mirror read there blurred a sharp panorama that the truth shows sharp (the room at
// r = 0.001 lost 8.5 dB against the mirror's 35.5, issue 14). In layered mode the mirror
// reads the hit object's own layer, where the composite may show a nearer surface from the
// centre. On a composite hit the two are the same texel. Level 1 takes the rest, as the
// chain blends its own levels; from level 1 on, the chain alone answers.
float glossyMirrorShare(float level) {
    return 1.0f - clamp(level, 0.0f, 1.0f);
}

#endif
