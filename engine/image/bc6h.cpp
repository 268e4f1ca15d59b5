#include "bc6h.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace specula {

namespace {

// ---- The format (Khronos Data Format specification, "BC6H") ----------------------------

// A mode's header: which bit of which endpoint component (or of the partition number) each
// bit of the block holds, after the mode bits. Endpoints are numbered as the specification's
// r0..r3 (w, x, y, z): region 0 interpolates 0 to 1, region 1 interpolates 2 to 3.
struct Mode {
    int modeBits;     // 2 or 5
    unsigned value;   // the mode bits' value
    int regions;      // 1 or 2
    bool transformed; // endpoints 1..3 are signed deltas from endpoint 0
    int endpointBits;
    std::array<int, 3>
        deltaBits; // per channel, of endpoints 1..3 (endpointBits if not transformed)
    // The specification's notation, lowest bit first: "g2[4]" is bit 4 of endpoint 2's green;
    // "r0[9:0]" bits 0 .. 9 of endpoint 0's red, bit 0 lowest; a reversed range, "r0[10:15]",
    // holds bit 15 lowest.
    const char* layout;
};

constexpr std::array<Mode, 14> kModes = {{
    {2,
     0x00,
     2,
     true,
     10,
     {5, 5, 5},
     "g2[4] b2[4] b3[4] r0[9:0] g0[9:0] b0[9:0] r1[4:0] g3[4] g2[3:0] g1[4:0] b3[0] g3[3:0] "
     "b1[4:0] b3[1] b2[3:0] r2[4:0] b3[2] r3[4:0] b3[3]"},
    {2,
     0x01,
     2,
     true,
     7,
     {6, 6, 6},
     "g2[5] g3[4] g3[5] r0[6:0] b3[0] b3[1] b2[4] g0[6:0] b2[5] b3[2] g2[4] b0[6:0] b3[3] b3[5] "
     "b3[4] r1[5:0] g2[3:0] g1[5:0] g3[3:0] b1[5:0] b2[3:0] r2[5:0] r3[5:0]"},
    {5,
     0x02,
     2,
     true,
     11,
     {5, 4, 4},
     "r0[9:0] g0[9:0] b0[9:0] r1[4:0] r0[10] g2[3:0] g1[3:0] g0[10] b3[0] g3[3:0] b1[3:0] b0[10] "
     "b3[1] b2[3:0] r2[4:0] b3[2] r3[4:0] b3[3]"},
    {5,
     0x06,
     2,
     true,
     11,
     {4, 5, 4},
     "r0[9:0] g0[9:0] b0[9:0] r1[3:0] r0[10] g3[4] g2[3:0] g1[4:0] g0[10] g3[3:0] b1[3:0] b0[10] "
     "b3[1] b2[3:0] r2[3:0] b3[0] b3[2] r3[3:0] g2[4] b3[3]"},
    {5,
     0x0A,
     2,
     true,
     11,
     {4, 4, 5},
     "r0[9:0] g0[9:0] b0[9:0] r1[3:0] r0[10] b2[4] g2[3:0] g1[3:0] g0[10] b3[0] g3[3:0] b1[4:0] "
     "b0[10] b2[3:0] r2[3:0] b3[1] b3[2] r3[3:0] b3[4] b3[3]"},
    {5,
     0x0E,
     2,
     true,
     9,
     {5, 5, 5},
     "r0[8:0] b2[4] g0[8:0] g2[4] b0[8:0] b3[4] r1[4:0] g3[4] g2[3:0] g1[4:0] b3[0] g3[3:0] "
     "b1[4:0] b3[1] b2[3:0] r2[4:0] b3[2] r3[4:0] b3[3]"},
    {5,
     0x12,
     2,
     true,
     8,
     {6, 5, 5},
     "r0[7:0] g3[4] b2[4] g0[7:0] b3[2] g2[4] b0[7:0] b3[3] b3[4] r1[5:0] g2[3:0] g1[4:0] b3[0] "
     "g3[3:0] b1[4:0] b3[1] b2[3:0] r2[5:0] r3[5:0]"},
    {5,
     0x16,
     2,
     true,
     8,
     {5, 6, 5},
     "r0[7:0] b3[0] b2[4] g0[7:0] g2[5] g2[4] b0[7:0] g3[5] b3[4] r1[4:0] g3[4] g2[3:0] g1[5:0] "
     "g3[3:0] b1[4:0] b3[1] b2[3:0] r2[4:0] b3[2] r3[4:0] b3[3]"},
    {5,
     0x1A,
     2,
     true,
     8,
     {5, 5, 6},
     "r0[7:0] b3[1] b2[4] g0[7:0] b2[5] g2[4] b0[7:0] b3[5] b3[4] r1[4:0] g3[4] g2[3:0] g1[4:0] "
     "b3[0] g3[3:0] b1[5:0] b2[3:0] r2[4:0] b3[2] r3[4:0] b3[3]"},
    {5,
     0x1E,
     2,
     false,
     6,
     {6, 6, 6},
     "r0[5:0] g3[4] b3[0] b3[1] b2[4] g0[5:0] g2[5] b2[5] b3[2] g2[4] b0[5:0] g3[5] b3[3] b3[5] "
     "b3[4] r1[5:0] g2[3:0] g1[5:0] g3[3:0] b1[5:0] b2[3:0] r2[5:0] r3[5:0]"},
    {5, 0x03, 1, false, 10, {10, 10, 10}, "r0[9:0] g0[9:0] b0[9:0] r1[9:0] g1[9:0] b1[9:0]"},
    {5,
     0x07,
     1,
     true,
     11,
     {9, 9, 9},
     "r0[9:0] g0[9:0] b0[9:0] r1[8:0] r0[10] g1[8:0] g0[10] b1[8:0] b0[10]"},
    {5,
     0x0B,
     1,
     true,
     12,
     {8, 8, 8},
     "r0[9:0] g0[9:0] b0[9:0] r1[7:0] r0[10:11] g1[7:0] g0[10:11] b1[7:0] b0[10:11]"},
    {5,
     0x0F,
     1,
     true,
     16,
     {4, 4, 4},
     "r0[9:0] g0[9:0] b0[9:0] r1[3:0] r0[10:15] g1[3:0] g0[10:15] b1[3:0] b0[10:15]"},
}};
constexpr int kEncoderMode = 10; // mode 11 of the specification: one region, 10-bit endpoints

// Two-region partitions: texel i (row-major in the block) lies in region 1 where bit i is
// set; the first 32 shapes of BPTC's two-region table.
constexpr std::array<std::uint16_t, 32> kPartitions = {
    0xCCCC, 0x8888, 0xEEEE, 0xECC8, 0xC880, 0xFEEC, 0xFEC8, 0xEC80, 0xC800, 0xFFEC, 0xFE80,
    0xE800, 0xFFE8, 0xFF00, 0xFFF0, 0xF000, 0xF710, 0x008E, 0x7100, 0x08CE, 0x008C, 0x7310,
    0x3100, 0x8CCE, 0x088C, 0x3110, 0x6666, 0x366C, 0x17E8, 0x0FF0, 0x718E, 0x399C};
// The texel of region 1 whose index drops its top bit (region 0's is texel 0).
constexpr std::array<std::uint8_t, 32> kAnchor2 = {15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15,
                                                   15, 15, 15, 15, 15, 15, 2,  8,  2,  2,  8,
                                                   8,  15, 2,  8,  2,  2,  8,  8,  2,  2};
constexpr std::array<int, 8> kWeights3 = {0, 9, 18, 27, 37, 46, 55, 64};
constexpr std::array<int, 16> kWeights4 = {0,  4,  9,  13, 17, 21, 26, 30,
                                           34, 38, 43, 47, 51, 55, 60, 64};

constexpr int kPartitionField = 12; // fields 0..11 are endpoint * 3 + channel

struct BitRef {
    std::uint8_t field = 0, bit = 0;
};
// Each mode's header bits from the mode bits on (77 for two regions then the 5 partition
// bits, 60 for one), parsed once from the layouts above.
struct ModeHeader {
    std::array<BitRef, 82> refs{};
    int count = 0;
};

const std::array<ModeHeader, 14>& modeHeaders() {
    static const std::array<ModeHeader, 14> headers = [] {
        std::array<ModeHeader, 14> h{};
        for (std::size_t m = 0; m < kModes.size(); ++m) {
            ModeHeader& out = h[m];
            for (const char* p = kModes[m].layout; *p;) {
                if (*p == ' ') {
                    ++p;
                    continue;
                }
                const int channel = p[0] == 'r' ? 0 : p[0] == 'g' ? 1 : 2;
                const int field = (p[1] - '0') * 3 + channel;
                char* end = nullptr;
                const long hi = std::strtol(p + 3, &end, 10);
                long lo = hi;
                if (*end == ':') lo = std::strtol(end + 1, &end, 10);
                // The lowest position holds the range's right-hand bit.
                const long step = lo <= hi ? 1 : -1;
                for (long b = lo;; b += step) {
                    out.refs[std::size_t(out.count++)] = {std::uint8_t(field), std::uint8_t(b)};
                    if (b == hi) break;
                }
                p = end + 1; // past ']'
            }
            if (kModes[m].regions == 2)
                for (std::uint8_t b = 0; b < 5; ++b)
                    out.refs[std::size_t(out.count++)] = {kPartitionField, b};
        }
        return h;
    }();
    return headers;
}

unsigned bitAt(const std::uint8_t* block, int pos) {
    return (block[pos >> 3] >> (pos & 7)) & 1u;
}
void setBit(std::uint8_t* block, int pos, unsigned v) {
    if (v) block[pos >> 3] = std::uint8_t(block[pos >> 3] | (1u << (pos & 7)));
}

// The mode of a block; -1 for the reserved ones.
int modeOf(const std::uint8_t* block) {
    const unsigned two = block[0] & 3u;
    if (two < 2) return int(two);
    const unsigned five = block[0] & 31u;
    for (std::size_t m = 2; m < kModes.size(); ++m)
        if (kModes[m].value == five) return int(m);
    return -1;
}

int signExtend(int v, int bits) {
    const int sign = 1 << (bits - 1);
    return (v & (sign - 1)) - (v & sign);
}

// An endpoint component to the 16-bit interpolation domain (unsigned BC6H).
int unquantize(int v, int bits) {
    if (bits >= 15) return v;
    if (v == 0) return 0;
    if (v == (1 << bits) - 1) return 0xFFFF;
    return ((v << 16) + 0x8000) >> bits;
}

// The interpolated value's half-float bits.
std::uint16_t interpolate(int a, int b, int weight) {
    const int v = ((64 - weight) * a + weight * b + 32) >> 6;
    return std::uint16_t((v * 31) >> 6);
}

void decodeBlock(const std::uint8_t* block, std::array<std::array<std::uint16_t, 3>, 16>& out) {
    const int m = modeOf(block);
    if (m < 0) {
        for (auto& t : out)
            t = {0, 0, 0};
        return;
    }
    const Mode& mode = kModes[std::size_t(m)];
    const ModeHeader& header = modeHeaders()[std::size_t(m)];
    std::array<std::array<int, 3>, 4> e{};
    int partition = 0;
    for (int i = 0; i < header.count; ++i) {
        const BitRef r = header.refs[std::size_t(i)];
        const int v = int(bitAt(block, mode.modeBits + i)) << r.bit;
        if (r.field == kPartitionField)
            partition |= v;
        else
            e[r.field / 3u][r.field % 3u] |= v;
    }
    const int endpoints = 2 * mode.regions;
    const int mask = (1 << mode.endpointBits) - 1;
    for (int c = 0; c < 3; ++c) {
        if (mode.transformed)
            for (int k = 1; k < endpoints; ++k)
                e[std::size_t(k)][std::size_t(c)] =
                    (e[0][std::size_t(c)] + signExtend(e[std::size_t(k)][std::size_t(c)],
                                                       mode.deltaBits[std::size_t(c)])) &
                    mask;
        for (int k = 0; k < endpoints; ++k)
            e[std::size_t(k)][std::size_t(c)] =
                unquantize(e[std::size_t(k)][std::size_t(c)], mode.endpointBits);
    }
    const bool two = mode.regions == 2;
    int pos = two ? 82 : 65;
    for (int i = 0; i < 16; ++i) {
        const bool anchor = i == 0 || (two && i == kAnchor2[std::size_t(partition)]);
        const int bits = (two ? 3 : 4) - (anchor ? 1 : 0);
        int index = 0;
        for (int b = 0; b < bits; ++b)
            index |= int(bitAt(block, pos++)) << b;
        const int region = two ? (kPartitions[std::size_t(partition)] >> i) & 1 : 0;
        const int w = two ? kWeights3[std::size_t(index)] : kWeights4[std::size_t(index)];
        for (std::size_t c = 0; c < 3; ++c)
            out[std::size_t(i)][c] =
                interpolate(e[std::size_t(2 * region)][c], e[std::size_t(2 * region + 1)][c], w);
    }
}

// ---- The encoder (mode 11) -------------------------------------------------------------

using Endpoints = std::array<std::array<int, 3>, 2>; // 10-bit, per end and channel
using Texels = std::array<std::array<int, 3>, 16>;   // half-float bits

std::uint16_t halfBitsOf(float v) {
    if (!(v > 0.f)) return 0; // negative, zero, NaN
    return std::uint16_t(glm::packHalf1x16(std::min(v, 65504.f)));
}

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
    std::memset(block, 0, kBc6hBlockBytes);
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

} // namespace

std::size_t bc6hBytes(int width, int height) {
    return std::size_t((width + 3) / 4) * std::size_t((height + 3) / 4) * kBc6hBlockBytes;
}

std::vector<std::uint8_t> encodeBC6H(const Image& image) {
    const int bw = (image.width + 3) / 4, bh = (image.height + 3) / 4;
    std::vector<std::uint8_t> out(bc6hBytes(image.width, image.height));
    for (int by = 0; by < bh; ++by)
        for (int bx = 0; bx < bw; ++bx) {
            Texels t{};
            for (int i = 0; i < 16; ++i) {
                const int x = std::min(4 * bx + i % 4, image.width - 1);
                const int y = std::min(4 * by + i / 4, image.height - 1);
                const float* p = image.at(x, y);
                for (int c = 0; c < 3; ++c)
                    t[std::size_t(i)][std::size_t(c)] = c < image.channels ? halfBitsOf(p[c]) : 0;
            }
            encodeBlock(
                t, &out[(std::size_t(by) * std::size_t(bw) + std::size_t(bx)) * kBc6hBlockBytes]);
        }
    return out;
}

std::vector<std::uint16_t> decodeBC6HHalf(std::span<const std::uint8_t> blocks, int width,
                                          int height) {
    if (width < 0 || height < 0 || blocks.size() != bc6hBytes(width, height))
        throw std::invalid_argument("decodeBC6H: " + std::to_string(blocks.size()) +
                                    " bytes of blocks for a " + std::to_string(width) + "x" +
                                    std::to_string(height) + " image");
    std::vector<std::uint16_t> out(std::size_t(width) * std::size_t(height) * 3);
    const int bw = (width + 3) / 4, bh = (height + 3) / 4;
    std::array<std::array<std::uint16_t, 3>, 16> texels{};
    for (int by = 0; by < bh; ++by)
        for (int bx = 0; bx < bw; ++bx) {
            decodeBlock(
                &blocks[(std::size_t(by) * std::size_t(bw) + std::size_t(bx)) * kBc6hBlockBytes],
                texels);
            for (int i = 0; i < 16; ++i) {
                const int x = 4 * bx + i % 4, y = 4 * by + i / 4;
                if (x >= width || y >= height) continue;
                std::copy(texels[std::size_t(i)].begin(), texels[std::size_t(i)].end(),
                          &out[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3]);
            }
        }
    return out;
}

Image decodeBC6H(std::span<const std::uint8_t> blocks, int width, int height) {
    const std::vector<std::uint16_t> half = decodeBC6HHalf(blocks, width, height);
    Image image(width, height, 3);
    for (std::size_t i = 0; i < half.size(); ++i)
        image.pixels[i] = glm::unpackHalf1x16(half[i]);
    return image;
}

} // namespace specula
