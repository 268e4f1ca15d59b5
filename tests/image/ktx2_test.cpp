// KTX 2.0 files: the header, DFD and key/value bytes against the values the Khronos KTX 2.0 and
// Data Format specifications give (written out by hand here, not taken from the writer), round
// trips of 2D and cube textures with mips in float and half, and files that lie refused with
// their field named.
#include "engine/core/error.h"
#include "engine/image/ktx2.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <unistd.h>

namespace specula {
namespace {

std::uint32_t u32(const std::string& b, std::size_t at) {
    std::uint32_t v;
    std::memcpy(&v, b.data() + at, 4);
    return v;
}
std::uint64_t u64(const std::string& b, std::size_t at) {
    std::uint64_t v;
    std::memcpy(&v, b.data() + at, 8);
    return v;
}
void setU32(std::string& b, std::size_t at, std::uint32_t v) {
    std::memcpy(b.data() + at, &v, 4);
}
void setU64(std::string& b, std::size_t at, std::uint64_t v) {
    std::memcpy(b.data() + at, &v, 8);
}

Image ramp(int w, int h, int c, float scale = 1.f) {
    Image im(w, h, c);
    for (std::size_t i = 0; i < im.pixels.size(); ++i)
        im.pixels[i] = scale * float(i % 977) / 7.f - 3.f;
    return im;
}

Ktx2Texture cubeWithMips(int n, int channels, bool half) {
    Ktx2Texture t{.cube = true, .halfFloat = half};
    for (int s = n; s >= 1; s /= 2)
        t.levels.push_back(ramp(s, 6 * s, channels, float(s)));
    return t;
}

std::string expectRefused(const std::string& bytes, const std::string& field) {
    try {
        parseKtx2(bytes, "probe.ktx2");
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), "probe.ktx2");
        EXPECT_EQ(e.field(), field) << e.what();
        return e.what();
    }
    ADD_FAILURE() << "accepted a file whose " << field << " is wrong";
    return {};
}

TEST(Ktx2, HeaderDfdAndKeyValuesAreTheSpecsBytes) {
    const Ktx2Texture t{.cube = true, .levels = {ramp(4, 24, 4)}};
    const std::string b = encodeKtx2(t, "x", "Specula test");
    const unsigned char id[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
    ASSERT_EQ(std::memcmp(b.data(), id, 12), 0);
    EXPECT_EQ(u32(b, 12), 109u);             // VK_FORMAT_R32G32B32A32_SFLOAT
    EXPECT_EQ(u32(b, 16), 4u);               // typeSize
    EXPECT_EQ(u32(b, 20), 4u);               // pixelWidth
    EXPECT_EQ(u32(b, 24), 4u);               // pixelHeight: one face
    EXPECT_EQ(u32(b, 28), 0u);               // pixelDepth
    EXPECT_EQ(u32(b, 32), 0u);               // layerCount: not an array
    EXPECT_EQ(u32(b, 36), 6u);               // faceCount
    EXPECT_EQ(u32(b, 40), 1u);               // levelCount
    EXPECT_EQ(u32(b, 44), 0u);               // no supercompression
    EXPECT_EQ(u32(b, 48), 80u + 24u);        // DFD right after the one-level index
    EXPECT_EQ(u32(b, 52), 4u + 24 + 16 * 4); // dfdTotalSize + basic block of four samples
    // DFD (KDF 1.3 section 5): total size, vendor/type 0, version 2 and block size 88,
    // RGBSDA(1) BT709(1) linear(1), 1x1x1x1 block, 16 bytes in plane 0.
    const std::size_t d = 104;
    EXPECT_EQ(u32(b, d), 92u);
    EXPECT_EQ(u32(b, d + 4), 0u);
    EXPECT_EQ(u32(b, d + 8), 2u | 88u << 16);
    EXPECT_EQ(u32(b, d + 12), 0x00010101u);
    EXPECT_EQ(u32(b, d + 16), 0u);
    EXPECT_EQ(u32(b, d + 20), 16u);
    // Samples: bit offset, 32 bits (31), channel R,G,B,A(15) with float|signed (0xC0).
    const std::uint32_t channel[4] = {0xC0, 0xC1, 0xC2, 0xCF};
    for (int s = 0; s < 4; ++s) {
        EXPECT_EQ(u32(b, d + 28 + 16 * s), std::uint32_t(32 * s) | 31u << 16 | channel[s] << 24);
        EXPECT_EQ(u32(b, d + 36 + 16 * s), 0xBF800000u); // -1.0f
        EXPECT_EQ(u32(b, d + 40 + 16 * s), 0x3F800000u); // 1.0f
    }
    // Key/value data: one entry, "KTXwriter\0Specula test\0" (23 bytes), padded to 24.
    EXPECT_EQ(u32(b, 56), 104u + 92u);
    EXPECT_EQ(u32(b, 60), 4u + 24u);
    EXPECT_EQ(u32(b, 196), 23u);
    EXPECT_EQ(b.substr(200, 23), std::string("KTXwriter\0Specula test\0", 23));
    // The level: 4 x 4 x 6 faces x 16 bytes at a 16-byte boundary, after the key/value data.
    EXPECT_EQ(u64(b, 80), 224u);
    EXPECT_EQ(u64(b, 88), 4u * 4 * 6 * 16);
    EXPECT_EQ(b.size(), 224u + 4 * 4 * 6 * 16);
    float first;
    std::memcpy(&first, b.data() + 224, 4);
    EXPECT_EQ(first, t.levels[0].pixels[0]);
}

TEST(Ktx2, LevelsAreStoredSmallestFirst) {
    const std::string b = encodeKtx2(cubeWithMips(8, 4, false), "x");
    ASSERT_EQ(u32(b, 40), 4u);
    for (int k = 0; k + 1 < 4; ++k) // each level's data lies after the next smaller one's
        EXPECT_GT(u64(b, 80 + 24 * k), u64(b, 80 + 24 * (k + 1)));
    EXPECT_EQ(u64(b, 80), b.size() - 8u * 8 * 6 * 16);
}

TEST(Ktx2, FloatCubeWithMipsRoundTripsExactly) {
    const Ktx2Texture t = cubeWithMips(16, 4, false);
    const Ktx2Texture r = parseKtx2(encodeKtx2(t, "x"), "x");
    EXPECT_TRUE(r.cube);
    EXPECT_FALSE(r.halfFloat);
    ASSERT_EQ(r.levels.size(), t.levels.size());
    for (std::size_t k = 0; k < t.levels.size(); ++k) {
        EXPECT_EQ(r.levels[k].width, t.levels[k].width);
        EXPECT_EQ(r.levels[k].height, t.levels[k].height);
        EXPECT_EQ(r.levels[k].pixels, t.levels[k].pixels);
    }
    EXPECT_EQ(r.keyValues.at("KTXwriter"), "Specula");
    EXPECT_EQ(r.keyValues.count("KTXorientation"), 0u); // cube faces have a fixed orientation
}

TEST(Ktx2, HalfFloatKeepsElevenSignificantBits) {
    for (int channels = 1; channels <= 4; ++channels) {
        Ktx2Texture t{.halfFloat = true,
                      .levels = {ramp(5, 3, channels)},
                      .keyValues = {{"settings", "abc"}}};
        const std::string b = encodeKtx2(t, "x");
        const std::uint32_t vk[4] = {76, 83, 90, 97}; // R16..R16G16B16A16_SFLOAT
        EXPECT_EQ(u32(b, 12), vk[channels - 1]);
        EXPECT_EQ(u32(b, 16), 2u);
        const Ktx2Texture r = parseKtx2(b, "x");
        EXPECT_TRUE(r.halfFloat);
        EXPECT_EQ(r.keyValues.at("KTXorientation"), "rd");
        EXPECT_EQ(r.keyValues.at("settings"), "abc");
        ASSERT_EQ(r.levels[0].pixels.size(), t.levels[0].pixels.size());
        for (std::size_t i = 0; i < t.levels[0].pixels.size(); ++i) {
            const float v = t.levels[0].pixels[i];
            EXPECT_NEAR(r.levels[0].pixels[i], v, std::abs(v) * 0x1p-11f + 1e-7f);
        }
    }
}

TEST(Ktx2, LimitsAreCheckedBeforeThePixels) {
    const std::string b = encodeKtx2(cubeWithMips(8, 4, false), "x");
    EXPECT_THROW(parseKtx2(b, "x", {.width = 16, .height = 16}), Error);
    EXPECT_THROW(parseKtx2(b, "x", {.faces = 1}), Error);
    EXPECT_THROW(parseKtx2(b, "x", {.channels = 3}), Error);
    EXPECT_THROW(parseKtx2(b, "x", {.maxValues = 8 * 8 * 6 * 4}), Error); // the mips count too
    EXPECT_NO_THROW(parseKtx2(b, "x", {.width = 8, .height = 8, .faces = 6, .channels = 4}));
}

TEST(Ktx2, FilesThatLieAreRefusedWithTheirField) {
    const std::string good = encodeKtx2(cubeWithMips(8, 4, false), "x");
    expectRefused(good.substr(0, 40), "identifier");
    expectRefused(good.substr(0, good.size() - 1), "level 0"); // truncated: level 0 is last
    std::string b = good;
    setU32(b, 12, 37); // VK_FORMAT_R8G8B8A8_UNORM
    expectRefused(b, "vkFormat");
    b = good;
    setU32(b, 16, 2);
    expectRefused(b, "typeSize");
    b = good;
    setU32(b, 40, 5); // 8 x 8 has 4 levels
    expectRefused(b, "levelCount");
    b = good;
    setU32(b, 36, 2);
    expectRefused(b, "faceCount");
    b = good;
    setU32(b, 44, 2); // Zstandard
    expectRefused(b, "supercompressionScheme");
    b = good;
    setU32(b, 24, 7); // a cube's faces must be square
    expectRefused(b, "pixelHeight");
    b = good;
    setU32(b, 20, 1u << 30);
    setU32(b, 24, 1u << 30);
    expectRefused(b, "pixelWidth");
    b = good;
    setU64(b, 80 + 24 * 2 + 8, 100); // level 2's length does not match 2 x 2 x 6 texels
    expectRefused(b, "level 2");
    b = good;
    setU64(b, 80, u64(good, 80) + 4); // level 0 misaligned and past the end
    expectRefused(b, "level 0");
    b = good;
    setU32(b, 48, std::uint32_t(good.size()) - 8); // DFD past the end
    expectRefused(b, "dfdByteOffset");
    b = good;
    const std::size_t dfd = u32(good, 48);
    setU32(b, dfd + 12, 0x00020101u); // sRGB transfer: a DFD that does not describe vkFormat
    expectRefused(b, "dfd");
    b = good;
    setU32(b, dfd + 28, 31u << 16); // sample 0: channel R without the float qualifier
    expectRefused(b, "dfd");
    b = good;
    setU32(b, u32(good, 56), 1000); // a key/value entry longer than the block
    expectRefused(b, "kvd");
}

TEST(Ktx2, WritesAtomicallyAndRefusesABadChain) {
    const std::string dir =
        (std::filesystem::temp_directory_path() / ("ktx2_test_" + std::to_string(::getpid())))
            .string();
    std::filesystem::create_directories(dir);
    const Image faces = ramp(4, 24, 3);
    writeKtx2Cube(dir + "/c.ktx2", faces);
    EXPECT_EQ(readKtx2Cube(dir + "/c.ktx2", 4).pixels, faces.pixels);
    EXPECT_THROW(readKtx2Image(dir + "/c.ktx2"), Error); // a cube is not a 2D image
    EXPECT_THROW(readKtx2Cube(dir + "/c.ktx2", 8), Error);
    EXPECT_THROW(writeKtx2Cube(dir + "/d.ktx2", ramp(4, 20, 4)), Error); // not N x 6N
    Ktx2Texture bad = cubeWithMips(8, 4, false);
    bad.levels[2] = ramp(3, 18, 4);
    EXPECT_THROW(writeKtx2(dir + "/e.ktx2", bad), Error);
    EXPECT_FALSE(std::filesystem::exists(dir + "/d.ktx2"));
    EXPECT_FALSE(std::filesystem::exists(dir + "/e.ktx2"));
    EXPECT_THROW(readKtx2(dir), Error); // a folder is not a file
    std::filesystem::remove_all(dir);
}

} // namespace
} // namespace specula
