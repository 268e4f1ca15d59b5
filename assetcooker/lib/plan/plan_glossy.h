#pragma once
// The effect plan's rough reflectors (issue 14): where a GGX lobe's blur hides the parallax a
// lookup would correct, the cheaper lookup serves.
//
// The lobe: a reflector of perceptual roughness r (alpha = r^2) spreads what it reflects over
// a cone about the mirror direction of half-angle
//     theta(alpha) = 2 atan(alpha)
// (the cone that holds half of the GGX lobe at N = V = R: half of the half-vectors lie within
// tan(theta_h) = alpha, and a half-vector at theta_h turns the reflection by 2 theta_h). It is
// glossyLobeHalfAngle of components/reflection_probe/distance/shaders/distance_glossy.glsl.h,
// the function the shader's footprint level rests on, so the plan and the lookup agree on
// what a lobe covers.
//
// The parallax the plan weighs is an angle at the reflector too: how far the direction to an
// object's nearest point turns between the probe centre and a reflector point `reach` away,
// asin(reach / nearest); and, for occlusion, how wide a band behind a small occluder a move
// of `reach` uncovers, reach (1 / d_front - 1 / d_back). Where that angle is below theta, the
// cheaper lookup misplaces the content by less than the lobe spreads it: the error hides in
// the blur (it is not zero: a blurred edge still moves by the parallax, by less than half
// the blur's width). The lookup is compiled per probe, so it must serve the probe's sharpest
// reflector: the narrowest lobe decides, and a mirror (r = 0) keeps the plan as it was.
#include "assetcooker/lib/scene/scene_markup.h"

#include <string>
#include <vector>

namespace specula {

struct PlannedReflector {
    std::string name;
    float roughness = 0.f; // perceptual (alpha = roughness^2); 0: a mirror
    float lobeDeg = 0.f;   // theta(alpha) above, degrees
};

// theta(alpha) above, degrees, for perceptual roughness `roughness` (clamped to [0, 1]; NaN:
// a mirror, 0).
float ggxLobeHalfWidthDeg(float roughness);

struct SharpestLobe {
    float deg = 0.f; // the narrowest lobe of the probe's reflectors (0: a mirror, or none)
    std::string reflector;
    float roughness = 0.f;
    // "the D deg half-width of the GGX lobe of the sharpest reflector (NAME, roughness R)"
    std::string text;
};

// Every reflector of `markup` with its lobe, and the sharpest of them.
SharpestLobe planReflectors(const SceneMarkup& markup, std::vector<PlannedReflector>& out);

} // namespace specula
