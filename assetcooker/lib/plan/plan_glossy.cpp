#include "assetcooker/lib/plan/plan_glossy.h"

#include "components/reflection_probe/distance/distance_glossy_cpu.h"
#include "components/reflection_probe/system/reflector_roughness.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace specula {

float ggxLobeHalfWidthDeg(float roughness) {
    if (!(roughness > 0.f)) return 0.f; // NaN too
    const float r = std::min(roughness, 1.f);
    return glossyLobeHalfAngle(r * r) * 180.f / 3.14159265f;
}

SharpestLobe planReflectors(const SceneMarkup& markup, std::vector<PlannedReflector>& out) {
    out.clear();
    SharpestLobe sharpest;
    for (const ReflectorMarkup& r : markup.reflectors) {
        // A roughness map: its smoothest texel is the sharpest lobe the reflector shows.
        const float sharpestTexel = r.roughness * roughnessMapMin(r.roughnessMap.get());
        const float roughness = sharpestTexel > 0.f ? std::min(sharpestTexel, 1.f) : 0.f;
        out.push_back({r.node, roughness, ggxLobeHalfWidthDeg(roughness)});
        if (out.size() == 1 || out.back().lobeDeg < sharpest.deg)
            sharpest = {out.back().lobeDeg, r.node, roughness, {}};
    }
    std::ostringstream s;
    s.setf(std::ios::fixed);
    if (out.empty()) {
        s << "no reflector: planned as a mirror";
    } else if (!(sharpest.deg > 0.f)) {
        s << "the sharpest reflector (" << sharpest.reflector << ") is a mirror";
    } else {
        s.precision(1);
        s << "the " << sharpest.deg << " deg half-width of the GGX lobe of the sharpest reflector ("
          << sharpest.reflector << ", roughness ";
        s.precision(2);
        s << sharpest.roughness << ")";
    }
    sharpest.text = s.str();
    return sharpest;
}

} // namespace specula
