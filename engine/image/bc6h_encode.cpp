// The BC6H encoder, fitted in the half floats' bit space (squared half-bit distance, where a
// step is a constant share of the value): the one-region 10-bit mode (mode 11), and the
// two-region modes on the partitions whose two lines fit the block best, the better block
// kept. Two regions hold what one line cannot: an edge between two colours, or channels that
// vary independently within the block.
#include "bc6h_format.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>

namespace specula::bc6h_detail {

namespace {

constexpr long long kNoFit = std::numeric_limits<long long>::max();
using Point = std::array<double, 3>;

// A texel in the interpolation domain (0 .. 65535; the decoder's half bits are x * 31 / 64).
Point domainOf(const std::array<int, 3>& halfBits) {
    Point p{};
    for (std::size_t c = 0; c < 3; ++c)
        p[c] = (halfBits[c] + 0.5) * 64.0 / 31.0;
    return p;
}

// The principal line through the texels of `subset` (bit i: texel i): its two ends (the
// extreme projections) and the squared distance of the texels from it.
struct Line {
    std::array<Point, 2> ends{};
    double residual = 0.0;
};

Line principalLine(const Texels& t, unsigned subset) {
    std::array<Point, 16> x{};
    Point mean{};
    int n = 0;
    for (std::size_t i = 0; i < 16; ++i) {
        if (!((subset >> i) & 1u)) continue;
        x[std::size_t(n)] = domainOf(t[i]);
        for (std::size_t c = 0; c < 3; ++c)
            mean[c] += x[std::size_t(n)][c];
        ++n;
    }
    for (double& m : mean)
        m /= std::max(n, 1);
    double cov[3][3] = {}, total = 0.0;
    for (int i = 0; i < n; ++i)
        for (std::size_t a = 0; a < 3; ++a) {
            total += (x[std::size_t(i)][a] - mean[a]) * (x[std::size_t(i)][a] - mean[a]);
            for (std::size_t b = 0; b < 3; ++b)
                cov[a][b] += (x[std::size_t(i)][a] - mean[a]) * (x[std::size_t(i)][b] - mean[b]);
        }
    Point axis{1.0, 1.0, 1.0};
    for (int it = 0; it < 12; ++it) {
        Point next{};
        for (std::size_t a = 0; a < 3; ++a)
            for (std::size_t b = 0; b < 3; ++b)
                next[a] += cov[a][b] * axis[b];
        const double len = std::sqrt(next[0] * next[0] + next[1] * next[1] + next[2] * next[2]);
        if (len < 1e-12) break; // a flat set: any axis
        for (std::size_t a = 0; a < 3; ++a)
            axis[a] = next[a] / len;
    }
    const double axisLen = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    for (double& a : axis)
        a /= axisLen;
    double lo = std::numeric_limits<double>::max(), hi = -lo, along = 0.0;
    for (int i = 0; i < n; ++i) {
        const Point& p = x[std::size_t(i)];
        const double s =
            (p[0] - mean[0]) * axis[0] + (p[1] - mean[1]) * axis[1] + (p[2] - mean[2]) * axis[2];
        lo = std::min(lo, s), hi = std::max(hi, s), along += s * s;
    }
    Line line;
    for (std::size_t c = 0; c < 3; ++c) {
        line.ends[0][c] = mean[c] + lo * axis[c];
        line.ends[1][c] = mean[c] + hi * axis[c];
    }
    line.residual = std::max(0.0, total - along);
    return line;
}

// The `bits`-bit endpoint whose unquantized value is nearest `v`.
int quantize(double v, int bits) {
    const int top = (1 << bits) - 1;
    const int guess = std::clamp(int(std::lround(v * double(1 << bits) / 65536.0 - 0.5)), 0, top);
    int best = guess;
    double bestDistance = std::numeric_limits<double>::max();
    for (int q = std::max(0, guess - 1); q <= std::min(top, guess + 1); ++q)
        if (const double d = std::abs(unquantize(q, bits) - v); d < bestDistance)
            bestDistance = d, best = q;
    return best;
}

// Writes the mode bits and the header (endpoint components as stored: deltas already
// masked) of mode `m`, the partition for two regions.
void packHeader(std::uint8_t* block, int m, const std::array<std::array<int, 3>, 4>& stored,
                int partition) {
    std::memset(block, 0, 16);
    const Mode& mode = kModes[std::size_t(m)];
    for (int b = 0; b < mode.modeBits; ++b)
        setBit(block, b, (mode.value >> b) & 1u);
    const ModeHeader& header = modeHeaders()[std::size_t(m)];
    for (int i = 0; i < header.count; ++i) {
        const BitRef r = header.refs[std::size_t(i)];
        const int v = r.field == kPartitionField ? partition : stored[r.field / 3u][r.field % 3u];
        setBit(block, mode.modeBits + i, unsigned(v >> r.bit) & 1u);
    }
}

// ---- One region: mode 11 ----------------------------------------------------------------

using Endpoints = std::array<std::array<int, 3>, 2>; // 10-bit, per end and channel

// The block's error with the best index per texel.
long long fit(const Texels& t, const Endpoints& q, std::array<int, 16>& index) {
    std::array<std::array<int, 3>, 16> palette{};
    for (std::size_t k = 0; k < 16; ++k)
        for (std::size_t c = 0; c < 3; ++c)
            palette[k][c] =
                interpolate(unquantize(q[0][c], 10), unquantize(q[1][c], 10), kWeights4[k]);
    long long total = 0;
    for (std::size_t i = 0; i < 16; ++i) {
        long long best = kNoFit;
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

// Least-squares endpoints for the chosen indices (false when the indices do not span).
bool refit(const Texels& t, const std::array<int, 16>& index, Endpoints& q) {
    double aa = 0, ab = 0, bb = 0;
    Point ax{}, bx{};
    for (std::size_t i = 0; i < 16; ++i) {
        const double w = kWeights4[std::size_t(index[i])] / 64.0;
        aa += (1 - w) * (1 - w);
        ab += (1 - w) * w;
        bb += w * w;
        const Point x = domainOf(t[i]);
        for (std::size_t c = 0; c < 3; ++c) {
            ax[c] += (1 - w) * x[c];
            bx[c] += w * x[c];
        }
    }
    const double det = aa * bb - ab * ab;
    if (std::abs(det) < 1e-9) return false;
    for (std::size_t c = 0; c < 3; ++c) {
        q[0][c] = quantize((bb * ax[c] - ab * bx[c]) / det, 10);
        q[1][c] = quantize((aa * bx[c] - ab * ax[c]) / det, 10);
    }
    return true;
}

long long encodeOneRegion(const Texels& t, std::uint8_t* block) {
    const Line line = principalLine(t, 0xFFFFu);
    Endpoints q{};
    for (std::size_t e = 0; e < 2; ++e)
        for (std::size_t c = 0; c < 3; ++c)
            q[e][c] = quantize(line.ends[e][c], 10);
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
    packHeader(block, kEncoderMode, {q[0], q[1], {}, {}}, 0);
    int pos = 65;
    for (std::size_t i = 0; i < 16; ++i)
        for (int b = 0; b < (i == 0 ? 3 : 4); ++b)
            setBit(block, pos++, unsigned(index[i] >> b) & 1u);
    return err;
}

// ---- Two regions: modes 1 to 10 ---------------------------------------------------------

// The two-region modes, the finest endpoints first (11-bit bases with 4- or 5-bit deltas,
// 10/5, 9/5, 8/6 and 8/5, 7/6) and the 6-bit untransformed one, which always fits.
constexpr std::array<int, 10> kTwoRegionModes = {2, 3, 4, 0, 5, 6, 7, 8, 1, 9};
// Partitions quantized per block: those whose two lines leave the least residual.
constexpr int kPartitionsTried = 2;

// The block in mode `m` on `partition` with the lines' ends; kNoFit when the mode's deltas
// cannot hold them.
long long encodeTwoRegionMode(const Texels& t, int partition, const std::array<Line, 2>& lines,
                              int m, std::uint8_t* block) {
    const Mode& mode = kModes[std::size_t(m)];
    const int bits = mode.endpointBits;
    const unsigned shape = kPartitions[std::size_t(partition)];
    const int anchor1 = kAnchor2[std::size_t(partition)];
    std::array<std::array<int, 3>, 4> q{};
    for (std::size_t k = 0; k < 4; ++k)
        for (std::size_t c = 0; c < 3; ++c)
            q[k][c] = quantize(lines[k / 2].ends[k % 2][c], bits);
    std::array<std::array<std::array<int, 3>, 8>, 2> palette{};
    for (std::size_t r = 0; r < 2; ++r)
        for (std::size_t k = 0; k < 8; ++k)
            for (std::size_t c = 0; c < 3; ++c)
                palette[r][k][c] = interpolate(unquantize(q[2 * r][c], bits),
                                               unquantize(q[2 * r + 1][c], bits), kWeights3[k]);
    std::array<int, 16> index{};
    long long err = 0;
    for (std::size_t i = 0; i < 16; ++i) {
        const std::size_t r = (shape >> i) & 1u;
        long long best = kNoFit;
        for (std::size_t k = 0; k < 8; ++k) {
            long long e = 0;
            for (std::size_t c = 0; c < 3; ++c) {
                const long long d = palette[r][k][c] - t[i][c];
                e += d * d;
            }
            if (e < best) best = e, index[i] = int(k);
        }
        err += best;
    }
    // Each region's anchor drops its index's top bit: swap that region's ends when it is set.
    for (std::size_t r = 0; r < 2; ++r) {
        const std::size_t anchor = r == 0 ? 0 : std::size_t(anchor1);
        if (index[anchor] < 4) continue;
        std::swap(q[2 * r], q[2 * r + 1]);
        for (std::size_t i = 0; i < 16; ++i)
            if (((shape >> i) & 1u) == r) index[i] = 7 - index[i];
    }
    std::array<std::array<int, 3>, 4> stored = q;
    if (mode.transformed)
        for (std::size_t k = 1; k < 4; ++k)
            for (std::size_t c = 0; c < 3; ++c) {
                const int d = q[k][c] - q[0][c], width = mode.deltaBits[c];
                if (d < -(1 << (width - 1)) || d >= (1 << (width - 1))) return kNoFit;
                stored[k][c] = d & ((1 << width) - 1);
            }
    packHeader(block, m, stored, partition);
    int pos = 82;
    for (int i = 0; i < 16; ++i) {
        const int width = (i == 0 || i == anchor1) ? 2 : 3;
        for (int b = 0; b < width; ++b)
            setBit(block, pos++, unsigned(index[std::size_t(i)] >> b) & 1u);
    }
    return err;
}

long long encodeTwoRegions(const Texels& t, std::uint8_t* block) {
    std::array<std::array<Line, 2>, 32> lines{};
    std::array<std::pair<double, int>, 32> ranked{};
    for (int p = 0; p < 32; ++p) {
        const unsigned shape = kPartitions[std::size_t(p)];
        lines[std::size_t(p)] = {principalLine(t, ~shape & 0xFFFFu), principalLine(t, shape)};
        ranked[std::size_t(p)] = {
            lines[std::size_t(p)][0].residual + lines[std::size_t(p)][1].residual, p};
    }
    std::partial_sort(ranked.begin(), ranked.begin() + kPartitionsTried, ranked.end());
    long long best = kNoFit;
    std::array<std::uint8_t, 16> candidate{};
    for (int k = 0; k < kPartitionsTried; ++k) {
        const int p = ranked[std::size_t(k)].second;
        for (int m : kTwoRegionModes) {
            const long long e =
                encodeTwoRegionMode(t, p, lines[std::size_t(p)], m, candidate.data());
            if (e < best) best = e, std::memcpy(block, candidate.data(), 16);
        }
    }
    return best;
}

} // namespace

void encodeBlock(const Texels& t, std::uint8_t* block) {
    const long long one = encodeOneRegion(t, block);
    if (one == 0) return;
    std::array<std::uint8_t, 16> two{};
    if (encodeTwoRegions(t, two.data()) < one) std::memcpy(block, two.data(), 16);
}

} // namespace specula::bc6h_detail
