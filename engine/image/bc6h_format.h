#pragma once
// BC6H's bit layout, shared by the decoder (bc6h.cpp) and the encoder (bc6h_encode.cpp): the
// fourteen modes, the two-region partitions, the interpolation weights and the arithmetic that
// turns endpoints into half floats. Internal to engine/image; the API is bc6h.h.
#include <array>
#include <cstddef>
#include <cstdint>

namespace specula::bc6h_detail {

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

inline constexpr std::array<Mode, 14> kModes = {{
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
inline constexpr int kEncoderMode =
    10; // mode 11 of the specification: one region, 10-bit endpoints

// Two-region partitions: texel i (row-major in the block) lies in region 1 where bit i is
// set; the first 32 shapes of BPTC's two-region table.
inline constexpr std::array<std::uint16_t, 32> kPartitions = {
    0xCCCC, 0x8888, 0xEEEE, 0xECC8, 0xC880, 0xFEEC, 0xFEC8, 0xEC80, 0xC800, 0xFFEC, 0xFE80,
    0xE800, 0xFFE8, 0xFF00, 0xFFF0, 0xF000, 0xF710, 0x008E, 0x7100, 0x08CE, 0x008C, 0x7310,
    0x3100, 0x8CCE, 0x088C, 0x3110, 0x6666, 0x366C, 0x17E8, 0x0FF0, 0x718E, 0x399C};
// The texel of region 1 whose index drops its top bit (region 0's is texel 0).
inline constexpr std::array<std::uint8_t, 32> kAnchor2 = {
    15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15, 15,
    15, 2,  8,  2,  2,  8,  8,  15, 2,  8,  2,  2,  8,  8,  2,  2};
inline constexpr std::array<int, 8> kWeights3 = {0, 9, 18, 27, 37, 46, 55, 64};
inline constexpr std::array<int, 16> kWeights4 = {0,  4,  9,  13, 17, 21, 26, 30,
                                                  34, 38, 43, 47, 51, 55, 60, 64};

inline constexpr int kPartitionField = 12; // fields 0..11 are endpoint * 3 + channel

struct BitRef {
    std::uint8_t field = 0, bit = 0;
};
// Each mode's header bits from the mode bits on (77 for two regions then the 5 partition
// bits, 60 for one), parsed once from the layouts above.
struct ModeHeader {
    std::array<BitRef, 82> refs{};
    int count = 0;
};

// Each mode's header, parsed once from the layouts above.
const std::array<ModeHeader, 14>& modeHeaders();

inline unsigned bitAt(const std::uint8_t* block, int pos) {
    return (block[pos >> 3] >> (pos & 7)) & 1u;
}
inline void setBit(std::uint8_t* block, int pos, unsigned v) {
    if (v) block[pos >> 3] = std::uint8_t(block[pos >> 3] | (1u << (pos & 7)));
}

// An endpoint component to the 16-bit interpolation domain (unsigned BC6H).
inline int unquantize(int v, int bits) {
    if (bits >= 15) return v;
    if (v == 0) return 0;
    if (v == (1 << bits) - 1) return 0xFFFF;
    return ((v << 16) + 0x8000) >> bits;
}

// The interpolated value's half-float bits.
inline std::uint16_t interpolate(int a, int b, int weight) {
    const int v = ((64 - weight) * a + weight * b + 32) >> 6;
    return std::uint16_t((v * 31) >> 6);
}

using Texels = std::array<std::array<int, 3>, 16>; // a block's half-float bits, row-major
// The encoder's best block for `t` (bc6h_encode.cpp).
void encodeBlock(const Texels& t, std::uint8_t* block);

} // namespace specula::bc6h_detail
