// The BC1 (DXT1) codec against properties known in closed form: what a block's two 565
// endpoints decode to, single-colour blocks, the encoder against its own decoder, and the
// check that tells decodable blocks from three-colour-mode ones.
#include "engine/image/bc1.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdlib>
#include <random>

namespace specula {
namespace {

using Rgb = std::array<int, 3>;

// The 8-bit colour a 565 value stands for: each field's bits repeated into the low bits, as
// the S3TC specification expands them.
Rgb expand565(unsigned v) {
    const int r = int(v >> 11) & 31, g = int(v >> 5) & 63, b = int(v) & 31;
    return {(r << 3) | (r >> 2), (g << 2) | (g >> 4), (b << 3) | (b >> 2)};
}

// A block written by hand: endpoints c0, c1 and one 2-bit index per texel (row-major).
std::array<std::uint8_t, 8> block(unsigned c0, unsigned c1, const std::array<int, 16>& index) {
    std::array<std::uint8_t, 8> b{std::uint8_t(c0 & 0xff), std::uint8_t(c0 >> 8),
                                  std::uint8_t(c1 & 0xff), std::uint8_t(c1 >> 8)};
    for (int i = 0; i < 16; ++i)
        b[std::size_t(4 + i / 4)] |= std::uint8_t(index[std::size_t(i)] << (2 * (i % 4)));
    return b;
}

Rgb texel(const std::vector<std::uint8_t>& rgb, int width, int x, int y) {
    const std::uint8_t* p = &rgb[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3];
    return {p[0], p[1], p[2]};
}

// An image of 4x4 blocks, block k (row-major, `blocksWide` per row) all colour(k).
template <typename ColourOf>
std::vector<std::uint8_t> solidBlocks(int blocksWide, int blocksHigh, ColourOf colour) {
    const int w = 4 * blocksWide, h = 4 * blocksHigh;
    std::vector<std::uint8_t> rgb(std::size_t(w) * std::size_t(h) * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const Rgb c = colour((y / 4) * blocksWide + x / 4);
            for (int k = 0; k < 3; ++k)
                rgb[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 3 + std::size_t(k)] =
                    std::uint8_t(c[std::size_t(k)]);
        }
    return rgb;
}

TEST(Bc1, TwoColourBlockDecodesToItsEndpointsAndTheirThirds) {
    // c0 = pure red (31, 0, 0), c1 = pure blue (0, 0, 31); c0 > c1, so the four-colour mode:
    // index 2 is (2 c0 + c1) / 3 and index 3 is (c0 + 2 c1) / 3, in integer arithmetic.
    const std::array<int, 16> index{0, 1, 2, 3, 1, 0, 3, 2, 0, 0, 1, 1, 2, 2, 3, 3};
    const auto b = block(0xF800, 0x001F, index);
    const auto rgb = decodeBC1(b.data(), 4, 4);
    const Rgb want[4] = {{255, 0, 0}, {0, 0, 255}, {170, 0, 85}, {85, 0, 170}};
    for (int i = 0; i < 16; ++i)
        EXPECT_EQ(texel(rgb, 4, i % 4, i / 4), want[index[std::size_t(i)]]) << "texel " << i;
}

TEST(Bc1, ThreeColourModeDecodesIndexThreeToBlack) {
    // c0 <= c1 selects the three-colour mode: index 2 is the midpoint, index 3 black.
    std::array<int, 16> index{};
    index[5] = 2, index[6] = 3;
    const auto b = block(0x001F, 0xF800, index);
    const auto rgb = decodeBC1(b.data(), 4, 4);
    EXPECT_EQ(texel(rgb, 4, 0, 0), (Rgb{0, 0, 255}));
    EXPECT_EQ(texel(rgb, 4, 1, 1), (Rgb{127, 0, 127}));
    EXPECT_EQ(texel(rgb, 4, 2, 1), (Rgb{0, 0, 0}));
}

TEST(Bc1, EverySolid565ColourRoundTripsExactly) {
    // All 65536 565 values, one solid block each: the encoder must find the one endpoint
    // that reproduces the colour, so decoding gives back the same bytes.
    const int side = 256; // blocks per row and per column
    const auto rgb = solidBlocks(side, side, [](int k) { return expand565(unsigned(k)); });
    const auto blocks = encodeBC1(rgb.data(), 4 * side, 4 * side);
    ASSERT_EQ(blocks.size(), std::size_t(side) * side * 8);
    const auto back = decodeBC1(blocks.data(), 4 * side, 4 * side);
    EXPECT_EQ(back, rgb);
    EXPECT_FALSE(firstUndecodableBC1Block(blocks).has_value());
}

TEST(Bc1, AnySolidColourLandsOnTheNearest565Level) {
    // Grey levels 0..255 in every channel: the error is the distance to the nearest of the
    // 32 (red, blue) or 64 (green) expanded levels, at most 4 and 2 codes.
    const auto rgb = solidBlocks(16, 16, [](int k) { return Rgb{k, k, k}; });
    const auto back = decodeBC1(encodeBC1(rgb.data(), 64, 64).data(), 64, 64);
    int worst[3] = {0, 0, 0};
    for (std::size_t i = 0; i < rgb.size(); ++i) {
        const int c = int(i % 3);
        worst[c] = std::max(worst[c], std::abs(int(back[i]) - int(rgb[i])));
    }
    EXPECT_LE(worst[0], 4);
    EXPECT_LE(worst[1], 2);
    EXPECT_LE(worst[2], 4);
    EXPECT_GT(worst[0], 0); // 8-bit grey is not all 565: the bound is reached, not vacuous
}

TEST(Bc1, BlockOfTwo565ColoursRoundTripsExactly) {
    // Half the texels one 565 colour, half another: the principal axis runs through both,
    // they become the endpoints, and every texel picks its own endpoint back.
    std::mt19937 rng(7);
    std::uniform_int_distribution<unsigned> any565(0, 0xFFFF);
    for (int trial = 0; trial < 200; ++trial) {
        const unsigned a = any565(rng), b = any565(rng);
        if (expand565(a) == expand565(b)) continue;
        std::vector<std::uint8_t> rgb(16 * 3);
        for (int i = 0; i < 16; ++i) {
            const Rgb c = (i * 7) % 16 < 8 ? expand565(a) : expand565(b);
            for (int k = 0; k < 3; ++k)
                rgb[std::size_t(i * 3 + k)] = std::uint8_t(c[std::size_t(k)]);
        }
        const auto blocks = encodeBC1(rgb.data(), 4, 4);
        EXPECT_EQ(decodeBC1(blocks.data(), 4, 4), rgb) << "colours " << a << ", " << b;
    }
}

TEST(Bc1, RoundTripIsCloseAndExactForFlatBlocks) {
    // The encoder against its decoder on a gradient (error bounded by the 565 endpoint and
    // 2-bit index quantisation: 12 codes) and on flat blocks (exact up to 565 rounding).
    const int w = 64, hgt = 32;
    std::vector<std::uint8_t> rgb(std::size_t(w) * hgt * 3);
    for (int y = 0; y < hgt; ++y)
        for (int x = 0; x < w; ++x) {
            std::uint8_t* p = &rgb[(std::size_t(y) * w + x) * 3];
            p[0] = std::uint8_t(x * 4), p[1] = std::uint8_t(y * 8), p[2] = std::uint8_t(128);
            if (x >= 48) p[0] = 200, p[1] = 10, p[2] = 60; // flat blocks
        }
    const auto blocks = encodeBC1(rgb.data(), w, hgt);
    ASSERT_EQ(blocks.size(), std::size_t(w / 4 * hgt / 4 * 8));
    const auto back = decodeBC1(blocks.data(), w, hgt);
    int worst = 0, worstFlat = 0;
    for (int y = 0; y < hgt; ++y)
        for (int x = 0; x < w; ++x)
            for (int k = 0; k < 3; ++k) {
                const std::size_t i = (std::size_t(y) * w + x) * 3 + std::size_t(k);
                const int e = std::abs(int(back[i]) - int(rgb[i]));
                (x >= 48 ? worstFlat : worst) = std::max(x >= 48 ? worstFlat : worst, e);
            }
    EXPECT_LE(worst, 12);
    EXPECT_LE(worstFlat, 4);
}

TEST(Bc1, EncoderOutputIsAlwaysDecodable) {
    // Random texels: every block the encoder writes is in the four-colour mode or a single
    // colour with index 0, never one the check refuses.
    std::mt19937 rng(11);
    std::vector<std::uint8_t> rgb(64 * 64 * 3);
    for (auto& v : rgb)
        v = std::uint8_t(rng());
    EXPECT_FALSE(firstUndecodableBC1Block(encodeBC1(rgb.data(), 64, 64)).has_value());
}

TEST(Bc1, UndecodableCheckFindsTheFirstThreeColourBlockWithIndexThree) {
    std::array<int, 16> plain{};
    std::array<int, 16> usesThree{};
    usesThree[9] = 3;
    const auto four = block(0xF800, 0x001F, usesThree);  // c0 > c1: index 3 is a colour
    const auto flat = block(0x1234, 0x1234, plain);      // c0 == c1, every index 0
    const auto threeNoBlack = block(0x001F, 0xF800, {}); // three-colour mode, no index 3
    const auto black = block(0x001F, 0xF800, usesThree); // three-colour mode, index 3
    std::vector<std::uint8_t> data;
    for (const auto* b : {&four, &flat, &threeNoBlack, &black, &four})
        data.insert(data.end(), b->begin(), b->end());
    EXPECT_EQ(firstUndecodableBC1Block(data), std::optional<std::size_t>(3));
    data.resize(3 * 8 + 7); // the bad block cut short: an incomplete block is not looked at
    EXPECT_FALSE(firstUndecodableBC1Block(data).has_value());
}

} // namespace
} // namespace specula
