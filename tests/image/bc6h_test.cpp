// The BC6H codec against properties known in closed form: a mode-11 block written by hand
// decodes to the specification's interpolation, a reserved mode to black; the encoder's
// blocks hold flat colours to a step of the half-float grid and an HDR image to a quality
// floor (through our decoder here; through the GL driver's in tests/gpu/bc6h_gl_test.cpp);
// out-of-range values clamp; BC6H KTX2 files carry their blocks and refuse lies.
#include "engine/core/error.h"
#include "engine/image/bc6h.h"
#include "engine/image/ktx2.h"
#include "support/hdr_test_image.h"

#include <glm/gtc/packing.hpp>
#include <glm/vec3.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <stdexcept>

namespace specula {
namespace {

// A mode-11 block (one region, 10-bit endpoints e0 and e1 per channel, 4-bit indices; texel
// 0's index has 3 bits), packed field by field as the specification lists them.
std::array<std::uint8_t, 16> mode11Block(std::array<int, 3> e0, std::array<int, 3> e1,
                                         const std::array<int, 16>& index) {
    std::array<std::uint8_t, 16> b{};
    int pos = 0;
    const auto put = [&](unsigned v, int bits) {
        for (int i = 0; i < bits; ++i, ++pos)
            if ((v >> i) & 1u) b[std::size_t(pos / 8)] |= std::uint8_t(1u << (pos % 8));
    };
    put(0x03, 5);
    for (int v : e0)
        put(unsigned(v), 10);
    for (int v : e1)
        put(unsigned(v), 10);
    for (std::size_t i = 0; i < 16; ++i)
        put(unsigned(index[i]), i == 0 ? 3 : 4);
    return b;
}

TEST(Bc6h, AHandWrittenMode11BlockDecodesToTheSpecificationsInterpolation) {
    // Endpoint 0 of red is 0, of green 1023 (both map to the domain's ends), of blue 512;
    // endpoint 1 the other way round. Index i weighs endpoint 1 by w_i / 64.
    const std::array<int, 16> weights = {0,  4,  9,  13, 17, 21, 26, 30,
                                         34, 38, 43, 47, 51, 55, 60, 64};
    std::array<int, 16> index{};
    for (int i = 0; i < 16; ++i)
        index[std::size_t(i)] = i < 8 ? i : 23 - i; // texel 0's index is < 8 (the anchor)
    const auto block = mode11Block({0, 1023, 512}, {1023, 0, 100}, index);
    const std::vector<std::uint16_t> half = decodeBC6HHalf(block, 4, 4);
    const auto unq = [](int v) {
        return v == 0 ? 0 : v == 1023 ? 0xFFFF : ((v << 16) + 0x8000) >> 10;
    };
    for (std::size_t i = 0; i < 16; ++i) {
        const int w = weights[std::size_t(index[i])];
        const std::array<int, 3> a = {unq(0), unq(1023), unq(512)},
                                 z = {unq(1023), unq(0), unq(100)};
        for (std::size_t c = 0; c < 3; ++c) {
            const int v = ((64 - w) * a[c] + w * z[c] + 32) >> 6;
            EXPECT_EQ(half[i * 3 + c], (v * 31) >> 6) << "texel " << i << " channel " << c;
        }
    }
    // Weight 64 of an endpoint at the top of the domain is the largest finite half, 65504.
    EXPECT_EQ(half[8 * 3 + 0], 0x7BFF);
}

TEST(Bc6h, ReservedModesDecodeToBlackAndAWrongLengthIsRefused) {
    for (unsigned mode : {0x13u, 0x17u, 0x1Bu, 0x1Fu}) {
        std::array<std::uint8_t, 16> b;
        b.fill(0xA5);
        b[0] = std::uint8_t((b[0] & ~31u) | mode);
        for (std::uint16_t h : decodeBC6HHalf(b, 4, 4))
            EXPECT_EQ(h, 0) << "mode " << mode;
    }
    const std::vector<std::uint8_t> blocks(16 * 3);
    EXPECT_THROW(decodeBC6HHalf(blocks, 8, 8), std::invalid_argument);
    EXPECT_EQ(bc6hBytes(5, 3), 2u * 16u); // a partial block counts whole
}

TEST(Bc6h, FlatColoursRoundTripToAStepOfTheHalfFloatGrid) {
    // Colours across the range, one per block: each channel's decoded half within 2 steps
    // of the source's (a relative error under 0.2% for normal halves).
    const std::array<float, 8> values = {0.f, 1e-4f, 0.01f, 0.5f, 1.f, 37.25f, 1000.f, 60000.f};
    Image img(4 * int(values.size()), 4, 3);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const float v = values[std::size_t(x / 4)];
            img.at(x, y)[0] = v, img.at(x, y)[1] = 0.5f * v, img.at(x, y)[2] = 0.25f * v;
        }
    const auto blocks = encodeBC6H(img);
    ASSERT_EQ(blocks.size(), bc6hBytes(img.width, img.height));
    const std::vector<std::uint16_t> half = decodeBC6HHalf(blocks, img.width, img.height);
    for (int x = 0; x < img.width; x += 4)
        for (int c = 0; c < 3; ++c) {
            const int want = glm::packHalf1x16(img.at(x, 0)[c]);
            const int got = half[std::size_t(x) * 3 + std::size_t(c)];
            EXPECT_LE(std::abs(got - want), 2) << "value " << img.at(x, 0)[c];
        }
}

// Three colours a few tens of percent apart (warm on the left, cool top right, green bottom
// right: no line through RGB holds all three, so one region must blend them); two regions
// (partition 0 sets the right half apart) keep each colour at an endpoint.
TEST(Bc6h, ThreeColoursAreKeptByTwoRegions) {
    Image img(4, 4, 3);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            const glm::vec3 c = x < 2   ? glm::vec3(1.0f, 0.8f, 0.7f)
                                : y < 2 ? glm::vec3(0.7f, 0.8f, 1.0f)
                                        : glm::vec3(0.8f, 1.0f, 0.7f);
            std::copy(&c[0], &c[0] + 3, img.at(x, y));
        }
    const auto block = encodeBC6H(img);
    const unsigned mode = (block[0] & 3u) < 2 ? block[0] & 3u : block[0] & 31u;
    EXPECT_TRUE(mode != 0x03 && mode != 0x07 && mode != 0x0B && mode != 0x0F)
        << "a one-region mode, 0x" << std::hex << mode;
    const std::vector<std::uint16_t> half = decodeBC6HHalf(block, 4, 4);
    int worst = 0;
    for (int i = 0; i < 16; ++i)
        for (int c = 0; c < 3; ++c) {
            const int want = glm::packHalf1x16(img.pixels[std::size_t(3 * i + c)]);
            worst = std::max(worst, std::abs(int(half[std::size_t(3 * i + c)]) - want));
        }
    // Each colour is an endpoint: off by at most half the mode's endpoint step (65536 / 2^bits
    // in the interpolation domain, x 31 / 64 in half-float units) and the final rounding.
    const std::map<unsigned, int> endpointBits = {{0x00, 10}, {0x01, 7}, {0x02, 11}, {0x06, 11},
                                                  {0x0A, 11}, {0x0E, 9}, {0x12, 8},  {0x16, 8},
                                                  {0x1A, 8},  {0x1E, 6}};
    ASSERT_TRUE(endpointBits.count(mode));
    const double step = 65536.0 / double(1 << endpointBits.at(mode)) * 31.0 / 64.0;
    EXPECT_LE(worst, int(step / 2) + 2) << "mode 0x" << std::hex << mode;
    std::printf("[bc6h] three colours: mode 0x%x, worst %d half-float steps\n", mode, worst);
}

TEST(Bc6h, OutOfRangeValuesClampToTheFormatsRange) {
    Image img(4, 4, 3);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const std::array<float, 4> odd = {-3.f, nan, 1e9f, inf};
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
            for (int c = 0; c < 3; ++c)
                img.at(x, y)[c] = odd[std::size_t(x)];
    const Image back = decodeBC6H(encodeBC6H(img), 4, 4);
    for (int y = 0; y < 4; ++y) {
        EXPECT_EQ(back.at(0, y)[0], 0.f);
        EXPECT_EQ(back.at(1, y)[0], 0.f);
        EXPECT_NEAR(back.at(2, y)[0], 65504.f, 65504.f * 0.002f);
        EXPECT_NEAR(back.at(3, y)[0], 65504.f, 65504.f * 0.002f);
    }
}

TEST(Bc6h, AnHdrImageKeepsItsQualityFloor) {
    // Not multiples of 4: the last blocks repeat the edge.
    const Image src = test::hdrTestImage(130, 66);
    const auto blocks = encodeBC6H(src);
    const Image back = decodeBC6H(blocks, src.width, src.height);
    const double logPsnr = test::logLuminancePsnr(src, back), lin = test::linearPsnr(src, back);
    std::printf(
        "[bc6h] %dx%d: log-luminance PSNR %.2f dB, linear PSNR %.2f dB, %.1f bits per texel\n",
        src.width, src.height, logPsnr, lin,
        8.0 * double(blocks.size()) / (double(src.width) * src.height));
    // The floor on smooth HDR content (measured 57.0 and 51.7 dB when written); a wrong anchor,
    // endpoint order or rounding costs tens of dB.
    EXPECT_GE(logPsnr, 48.0);
    EXPECT_GE(lin, 45.0);
}

TEST(Bc6h, Ktx2CubesCarryTheirBlocksWithMips) {
    Ktx2Texture t{.cube = true, .bc6h = true};
    for (int n = 8; n >= 1; n /= 2)
        t.levels.push_back(test::hdrTestImage(n, 6 * n, std::uint32_t(n)));
    const std::string bytes = encodeKtx2(t, "probe.ktx2");
    const Ktx2Texture back = parseKtx2(bytes, "probe.ktx2");
    ASSERT_TRUE(back.bc6h);
    ASSERT_EQ(back.blocks.size(), 4u);
    ASSERT_EQ(back.levels.size(), 4u);
    for (std::size_t k = 0; k < 4; ++k) {
        const int n = 8 >> k;
        EXPECT_EQ(back.blocks[k].size(), 6 * bc6hBytes(n, n)) << "level " << k;
        EXPECT_EQ(back.levels[k].width, n);
        EXPECT_EQ(back.levels[k].height, 6 * n);
        EXPECT_EQ(back.levels[k].channels, 3);
        // Each face is its own run of blocks: face f decodes from its slice alone.
        const std::size_t face = bc6hBytes(n, n);
        for (int f = 0; f < 6; ++f) {
            const Image one =
                decodeBC6H(std::span(back.blocks[k]).subspan(std::size_t(f) * face, face), n, n);
            EXPECT_EQ(std::memcmp(one.pixels.data(), back.levels[k].at(0, f * n),
                                  one.pixels.size() * sizeof(float)),
                      0)
                << "level " << k << " face " << f;
        }
    }
    // Undecoded when asked: the blocks alone, for an upload.
    EXPECT_TRUE(parseKtx2(bytes, "probe.ktx2", {.decodeBlocks = false}).levels.empty());
}

TEST(Bc6h, Ktx2FilesThatLieAreRefusedNamingTheField) {
    Ktx2Texture t{.bc6h = true, .levels = {test::hdrTestImage(8, 8)}};
    const std::string good = encodeKtx2(t, "a.ktx2");
    const auto refused = [](std::string bytes, const std::string& field) {
        try {
            parseKtx2(bytes, "a.ktx2");
            ADD_FAILURE() << "read a file with a bad " << field;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("a.ktx2: " + field), std::string::npos)
                << e.what();
        }
    };
    const auto word = [](std::string b, std::size_t at, std::uint32_t v) {
        std::memcpy(b.data() + at, &v, 4);
        return b;
    };
    std::uint32_t dfdOffset = 0;
    std::memcpy(&dfdOffset, good.data() + 48, 4);
    refused(word(good, 16, 2), "typeSize");                              // a block format's is 1
    refused(word(good, dfdOffset + 12, 1u | 1u << 8 | 1u << 16), "dfd"); // RGBSDA, not BC6H
    refused(word(good, dfdOffset + 16, 0), "dfd");                       // a 1x1 texel block
    std::uint64_t length = 0;
    std::memcpy(&length, good.data() + 88, 8);
    std::string shortLevel = good;
    const std::uint64_t less = length - 16; // one block short
    std::memcpy(shortLevel.data() + 88, &less, 8);
    refused(shortLevel, "level 0");
    refused(good.substr(0, good.size() - 8), "level 0"); // truncated
}

} // namespace
} // namespace specula
