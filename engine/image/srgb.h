#pragma once
// The sRGB transfer function (IEC 61966-2-1): 8-bit image files and the light field's 8-bit
// slabs are sRGB-encoded, every image in memory is linear. One definition, so the runtime's
// decode and the tools' image I/O agree.
#include <cmath>

namespace specula {

inline float srgbToLinearValue(float encoded) {
    if (!(encoded > 0.f)) return 0.f;
    return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

inline float linearToSrgbValue(float linear) {
    if (!(linear > 0.f)) return 0.f;
    return linear <= 0.0031308f ? linear * 12.92f : 1.055f * std::pow(linear, 1.f / 2.4f) - 0.055f;
}

} // namespace specula
