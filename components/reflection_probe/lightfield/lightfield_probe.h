#pragma once
// The light-field-slab flavour's settings component and its one method. A probe entity
// whose manifest is "lightfield" may hold a LightFieldProbe (defaults when it does not).
#include "components/reflection_probe/method_label.h"

namespace specula {

struct LightFieldProbe {
    // Focal-plane disparity in pixels per camera step for all six slabs; NaN or < 0 takes
    // the cooked per-slab optimum. A change re-uploads nothing.
    float disparity = -1.f;
    // Draw the environment from the light field (eye rays) while the eye is inside the cell,
    // instead of rasterising it.
    bool background = false;

    bool operator==(const LightFieldProbe& o) const {
        // NaN means "cooked" like any negative value: two NaNs are the same setting.
        const bool cookedA = !(disparity >= 0.f), cookedB = !(o.disparity >= 0.f);
        return background == o.background &&
               (cookedA || cookedB ? cookedA == cookedB : disparity == o.disparity);
    }
};

inline constexpr MethodLabel kLightFieldMethod = {
    "lightfield", {0.90f, 0.25f, 0.65f}, "light-field slabs around the cell (Yu et al. 2005)"};

} // namespace specula
