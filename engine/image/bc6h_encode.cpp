// The BC6H encoder: the one-region 10-bit mode (mode 11) fitted in the half floats' bit space.
#include "bc6h_format.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>

namespace specula::bc6h_detail {

namespace {

// ---- The encoder (mode 11) -------------------------------------------------------------

using Endpoints = std::array<std::array<int, 3>, 2>; // 10-bit, per end and channel

// The block's error (squared half-bit distance) with the best index per texel.
long long fit(const Texels& t, const Endpoints& q, std::array<int, 16>& index) {
    std::array<std::array<int, 3>, 16> palette{};
    for (std::size_t k = 0; k < 16; ++k)
        for (std::size_t c = 0; c < 3; ++c)
            palette[k][c] =
                interpolate(unquantize(q[0][c], 10), unquantize(q[1][c], 10), kWeights4[k]);
    long long total = 0;
    for (std::size_t i = 0; i < 16; ++i) {
        long long best = std::numeric_limits<long long>::max();
        for (std::size_t k = 0; k < 16; ++k) {
            long long err = 0;
            for (std::size_t c = 0; c < 3; ++c) {
                const long long d = palette[k][c] - t[i][c];
                err += d * d;
            }
            if (err < best) best = err, index[i] = int(k);
        }
        total += best;
    }
    return total;
}

// The 10-bit endpoint whose interpolation-domain value is nearest `v` (half bits x 64 / 31).
int quantize10(double v) {
    return std::clamp(int(std::lround((v - 32.0) / 64.0)), 0, 1023);
}

// Endpoints along the block's principal axis in the interpolation domain.
Endpoints principalEndpoints(const Texels& t) {
    std::array<std::array<double, 3>, 16> x{};
    std::array<double, 3> mean{};
    for (std::size_t i = 0; i < 16; ++i)
        for (std::size_t c = 0; c < 3; ++c) {
            x[i][c] = (t[i][c] + 0.5) * 64.0 / 31.0;
            mean[c] += x[i][c] / 16.0;
        }
    double cov[3][3] = {};
    for (const auto& p : x)
        for (std::size_t a = 0; a < 3; ++a)
            for (std::size_t b = 0; b < 3; ++b)
                cov[a][b] += (p[a] - mean[a]) * (p[b] - mean[b]);
    std::array<double, 3> axis{1.0, 1.0, 1.0};
    for (int it = 0; it < 12; ++it) {
        std::array<double, 3> next{};
        for (std::size_t a = 0; a < 3; ++a)
            for (std::size_t b = 0; b < 3; ++b)
                next[a] += cov[a][b] * axis[b];
        const double len = std::sqrt(next[0] * next[0] + next[1] * next[1] + next[2] * next[2]);
        if (len < 1e-12) break; // a flat block: any axis
        for (std::size_t a = 0; a < 3; ++a)
            axis[a] = next[a] / len;
    }
    double lo = std::numeric_limits<double>::max(), hi = -lo;
    for (const auto& p : x) {
        const double s =
            (p[0] - mean[0]) * axis[0] + (p[1] - mean[1]) * axis[1] + (p[2] - mean[2]) * axis[2];
        lo = std::min(lo, s);
        hi = std::max(hi, s);
    }
    Endpoints q{};
    for (std::size_t c = 0; c < 3; ++c) {
        q[0][c] = quantize10(mean[c] + lo * axis[c]);
        q[1][c] = quantize10(mean[c] + hi * axis[c]);
    }
    return q;
}

// Least-squares endpoints for the chosen indices (false when the indices do not span).
bool refit(const Texels& t, const std::array<int, 16>& index, Endpoints& q) {
    double aa = 0, ab = 0, bb = 0;
    std::array<double, 3> ax{}, bx{};
    for (std::size_t i = 0; i < 16; ++i) {
        const double w = kWeights4[std::size_t(index[i])] / 64.0;
        aa += (1 - w) * (1 - w);
        ab += (1 - w) * w;
        bb += w * w;
        for (std::size_t c = 0; c < 3; ++c) {
            const double x = (t[i][c] + 0.5) * 64.0 / 31.0;
            ax[c] += (1 - w) * x;
            bx[c] += w * x;
        }
    }
    const double det = aa * bb - ab * ab;
    if (std::abs(det) < 1e-9) return false;
    for (std::size_t c = 0; c < 3; ++c) {
        q[0][c] = quantize10((bb * ax[c] - ab * bx[c]) / det);
        q[1][c] = quantize10((aa * bx[c] - ab * ax[c]) / det);
    }
    return true;
}

} // namespace

void encodeBlock(const Texels& t, std::uint8_t* block) {
    Endpoints q = principalEndpoints(t);
    std::array<int, 16> index{};
    long long err = fit(t, q, index);
    for (int pass = 0; pass < 2 && err > 0; ++pass) {
        Endpoints r = q;
        std::array<int, 16> ri{};
        if (!refit(t, index, r)) break;
        const long long e = fit(t, r, ri);
        if (e >= err) break;
        q = r, index = ri, err = e;
    }
    // One step of each endpoint component either way while that lowers the error.
    for (int pass = 0; pass < 2 && err > 0; ++pass) {
        bool improved = false;
        for (std::size_t end = 0; end < 2; ++end)
            for (std::size_t c = 0; c < 3; ++c)
                for (int step : {-1, 1}) {
                    Endpoints r = q;
                    r[end][c] = std::clamp(r[end][c] + step, 0, 1023);
                    std::array<int, 16> ri{};
                    const long long e = fit(t, r, ri);
                    if (e < err) q = r, index = ri, err = e, improved = true;
                }
        if (!improved) break;
    }
    // Texel 0's index drops its top bit: swap the ends when it is set (the palette reverses
    // exactly, the weights being symmetric).
    if (index[0] >= 8) {
        std::swap(q[0], q[1]);
        for (int& k : index)
            k = 15 - k;
    }
    std::memset(block, 0, 16);
    const Mode& mode = kModes[kEncoderMode];
    for (int b = 0; b < mode.modeBits; ++b)
        setBit(block, b, (mode.value >> b) & 1u);
    const ModeHeader& header = modeHeaders()[kEncoderMode];
    for (int i = 0; i < header.count; ++i) {
        const BitRef r = header.refs[std::size_t(i)];
        setBit(block, mode.modeBits + i, unsigned(q[r.field / 3u][r.field % 3u] >> r.bit) & 1u);
    }
    int pos = 65;
    for (std::size_t i = 0; i < 16; ++i)
        for (int b = 0; b < (i == 0 ? 3 : 4); ++b)
            setBit(block, pos++, unsigned(index[i] >> b) & 1u);
}

} // namespace specula::bc6h_detail
