// The GGX directional albedo table (engine/image/ggx_albedo.h) against an independent
// quadrature: over light directions on a fine grid of the hemisphere, with the BRDF written
// out (D, Smith G2), where the table integrates over importance-sampled half-vectors.
#include "engine/image/ggx_albedo.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace specula {
namespace {

double lambda(double c, double alpha) {
    const double tan2 = (1.0 - c * c) / (c * c);
    return 0.5 * (std::sqrt(1.0 + alpha * alpha * tan2) - 1.0);
}

// E = integral over l of D(h) G2(v, l) / (4 n.l n.v) n.l dl, midpoint rule in (cos theta_l, phi).
double albedoOverLights(double nv, double roughness, int n) {
    const double alpha = roughness * roughness, a2 = alpha * alpha;
    const double vx = std::sqrt(1.0 - nv * nv), vz = nv;
    double sum = 0.0;
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < 2 * n; ++b) {
            const double lz = (a + 0.5) / n, phi = M_PI * (b + 0.5) / n;
            const double s = std::sqrt(1.0 - lz * lz);
            const double lx = s * std::cos(phi), ly = s * std::sin(phi);
            double hx = vx + lx, hy = ly, hz = vz + lz;
            const double len = std::sqrt(hx * hx + hy * hy + hz * hz);
            hz /= len;
            const double d = a2 / (M_PI * std::pow(hz * hz * (a2 - 1.0) + 1.0, 2.0));
            const double g2 = 1.0 / (1.0 + lambda(nv, alpha) + lambda(lz, alpha));
            // dl = d(cos theta) d(phi): the cell is (1 / n) x (pi / n).
            sum += d * g2 / (4.0 * nv) * (1.0 / n) * (M_PI / n);
        }
    return sum;
}

TEST(GgxAlbedo, TableAgreesWithAQuadratureOverLightDirections) {
    double worst = 0.0;
    for (const double r : {0.3, 0.5, 0.75, 1.0})
        for (const double nv : {0.15, 0.4, 0.7, 0.95}) {
            const double reference = albedoOverLights(nv, r, 1024);
            const double quadrature = ggxAlbedoQuadrature(nv, r);
            const double table = ggxAlbedo(float(nv), float(r));
            std::printf("r %.2f n.v %.2f: over lights %.5f, over half-vectors %.5f, table %.5f\n",
                        r, nv, reference, quadrature, table);
            // The table adds bilinear interpolation between its 32 x 32 entries.
            EXPECT_NEAR(quadrature, reference, 1e-3) << "r " << r << " n.v " << nv;
            EXPECT_NEAR(table, reference, 2e-3) << "r " << r << " n.v " << nv;
            worst = std::max(worst, std::abs(table - reference));
        }
    RecordProperty("worst_table_error", std::to_string(worst));
}

TEST(GgxAlbedo, IsOneForAMirrorAndAtMostOneForAnyRoughness) {
    // (Not monotonic in roughness: at grazing views a wider lobe loses less below the
    // horizon than a narrow one tilted towards it.)
    for (const float nv : {0.1f, 0.5f, 1.f}) {
        EXPECT_NEAR(ggxAlbedo(nv, 0.f), 1.f, 2e-3f) << nv;
        for (float r = 0.f; r <= 1.f; r += 0.125f) {
            EXPECT_GT(ggxAlbedo(nv, r), 0.f);
            EXPECT_LE(ggxAlbedo(nv, r), 1.f + 1e-4f) << "n.v " << nv << " r " << r;
        }
    }
}

} // namespace
} // namespace specula
