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

// The chain level engines read: perceptual roughness times (levels - 1), as the chain was
// prefiltered (ggxChainLevel in engine/image/ggx_prefilter.h).
float glossyRoughnessLevel(float roughness, int levels) {
    return clamp(roughness, 0.0f, 1.0f) * float(levels - 1);
}

// theta(alpha) above: the half-width of the GGX lobe of alpha about the mirror direction.
float glossyLobeHalfAngle(float alpha) {
    return 2.0f * atan(alpha);
}

// The level whose lobe, seen from the probe centre, covers what a lobe of this roughness
// leaving x along lhat covers at the hit t along the ray (q = x + t lhat). Wherever t = |q|
// (x at the centre, for one) it is glossyRoughnessLevel; a nearer hit reads a lower level, a
// farther one a higher level, and t <= 0 (the reflector touches the surface) level 0. For
// glossy lobes alpha_level ~ alpha t / |q|.
float glossyFootprintLevel(float roughness, vec3 x, vec3 lhat, float t, int levels) {
    float r = clamp(roughness, 0.0f, 1.0f);
    float theta = glossyLobeHalfAngle(r * r);
    float ray = max(t, 0.0f);
    float fromCentre = max(length(x + ray * lhat), 1e-6f);
    // atan(t tan(theta) / |q|), written so theta = pi/2 (alpha = 1) stays finite; the second
    // argument stays > 0 (atan(0, 0) is undefined in GLSL, and cos(pi/2) rounds below 0).
    float phi = atan(ray * sin(theta), fromCentre * max(cos(theta), 1e-6f));
    // The level's own lobe: theta(alpha_i) = phi, so alpha_i = tan(phi / 2), r_i = sqrt.
    float levelAlpha = tan(0.5f * phi);
    return glossyRoughnessLevel(sqrt(levelAlpha), levels);
}

#endif
