#include "ggx_albedo.h"

#include "engine/core/glsl_host.h"

#include <algorithm>
#include <cmath>

namespace specula {
namespace glsl {
namespace {
float fetchGgxAlbedo(int i, int j) {
    return ggxAlbedoTable()[std::size_t(j * kGgxAlbedoTableSize + i)];
}
#include "engine/image/ggx_albedo.glsl.h"
static_assert(kGgxAlbedoSize == kGgxAlbedoTableSize);
} // namespace
} // namespace glsl

namespace {

// Smith's Lambda for GGX.
double smithLambda(double cosTheta, double alpha) {
    const double c = std::max(cosTheta, 1e-12);
    const double tan2 = std::max(0.0, 1.0 - c * c) / (c * c);
    return 0.5 * (std::sqrt(1.0 + alpha * alpha * tan2) - 1.0);
}

} // namespace

double ggxAlbedoQuadrature(double nv, double roughness, int n) {
    const double alpha = std::max(roughness * roughness, 1e-6), a2 = alpha * alpha;
    nv = std::clamp(nv, 1e-4, 1.0);
    // View in the x-z plane, normal +z. E = integral over half-vectors h of
    // G2 (v.h) / ((n.h) (n.v)) D(h) (n.h) dh, midpoint rule on an n x 2n grid of (s, phi) with
    // tan(theta_h) = alpha tan(pi s / 2): the lobe spreads evenly over s whatever alpha is, and
    // the integrand stays smooth up to s = 1 (the grazing tail), so the rule converges fast.
    const double vx = std::sqrt(1.0 - nv * nv), vz = nv;
    const double lv = smithLambda(nv, alpha);
    double sum = 0.0;
    for (int a = 0; a < n; ++a) {
        const double s = (a + 0.5) / n, ts = std::tan(0.5 * M_PI * s);
        const double theta = std::atan(alpha * ts);
        const double dTheta = alpha * 0.5 * M_PI * (1.0 + ts * ts) / (1.0 + a2 * ts * ts);
        const double cosH = std::cos(theta), sinH = std::sin(theta);
        const double d = a2 / (M_PI * std::pow(cosH * cosH * (a2 - 1.0) + 1.0, 2.0));
        const double cell = d * cosH * sinH * dTheta * (1.0 / n) * (M_PI / n);
        for (int b = 0; b < 2 * n; ++b) {
            const double phi = M_PI * (b + 0.5) / n;
            const double hx = sinH * std::cos(phi), hz = cosH; // (h.y enters neither v.h nor l.z)
            const double vh = vx * hx + vz * hz;
            if (vh <= 0.0) continue;
            const double lz = 2.0 * vh * hz - vz; // l = 2 (v.h) h - v
            if (lz <= 0.0) continue;
            const double g2 = 1.0 / (1.0 + lv + smithLambda(lz, alpha));
            sum += g2 * vh / (hz * nv) * cell;
        }
    }
    return sum;
}

const std::array<float, kGgxAlbedoTableSize * kGgxAlbedoTableSize>& ggxAlbedoTable() {
    static const auto table = [] {
        std::array<float, kGgxAlbedoTableSize * kGgxAlbedoTableSize> t{};
        for (int j = 0; j < kGgxAlbedoTableSize; ++j)
            for (int i = 0; i < kGgxAlbedoTableSize; ++i)
                t[std::size_t(j * kGgxAlbedoTableSize + i)] = float(ggxAlbedoQuadrature(
                    double(i) / (kGgxAlbedoTableSize - 1), double(j) / (kGgxAlbedoTableSize - 1)));
        return t;
    }();
    return table;
}

float ggxAlbedo(float nv, float roughness) {
    return glsl::ggxAlbedo(nv, roughness);
}

} // namespace specula
