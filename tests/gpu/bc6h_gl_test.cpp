// BC6H against an independent decoder, the GL driver's (GL_COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT;
// llvmpipe here, the vendor's driver on a GPU): random blocks of every mode decode to the same
// half floats through both, bit for bit, and the encoder's blocks of an HDR image read back
// from the driver at the codec's quality floor.
#include "engine/gpu/gl_objects.h"
#include "engine/image/bc6h.h"
#include "gl_test_context.h"
#include "support/hdr_test_image.h"

#include <glm/gtc/packing.hpp>

#include <array>
#include <cstdio>
#include <random>

namespace specula {
namespace {

using Bc6hGl = test::GlTest;

// The driver's decode of `blocks` (a width x height image) as half-float bits, RGB.
std::vector<std::uint16_t> driverDecode(const std::vector<std::uint8_t>& blocks, int width,
                                        int height) {
    const gpu::Texture t = gpu::Texture::create(GL_TEXTURE_2D);
    glTextureStorage2D(t.id(), 1, GL_COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT, width, height);
    glCompressedTextureSubImage2D(t.id(), 0, 0, 0, width, height,
                                  GL_COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT, GLsizei(blocks.size()),
                                  blocks.data());
    std::vector<std::uint16_t> out(std::size_t(width) * std::size_t(height) * 3);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(t.id(), 0, GL_RGB, GL_HALF_FLOAT, GLsizei(out.size() * 2), out.data());
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    return out;
}

TEST_F(Bc6hGl, RandomBlocksOfEveryModeDecodeAsTheDriverDecodesThem) {
    // The mode bits of the fourteen modes (two 2-bit ones, twelve 5-bit ones) and the four
    // reserved values; every other bit random.
    const std::array<unsigned, 18> modes = {0x00, 0x01, 0x02, 0x06, 0x0A, 0x0E, 0x12, 0x16, 0x1A,
                                            0x1E, 0x03, 0x07, 0x0B, 0x0F, 0x13, 0x17, 0x1B, 0x1F};
    const int width = 64, height = 64; // 256 blocks
    std::mt19937 rng(7);
    int mismatches = 0;
    for (int round = 0; round < 8; ++round) {
        std::vector<std::uint8_t> blocks(bc6hBytes(width, height));
        for (std::uint8_t& b : blocks)
            b = std::uint8_t(rng());
        for (std::size_t k = 0; k * 16 < blocks.size(); ++k) {
            const unsigned mode = modes[k % modes.size()];
            const unsigned bits = mode < 2 ? 2 : 5;
            blocks[16 * k] = std::uint8_t((blocks[16 * k] & ~((1u << bits) - 1)) | mode);
        }
        const std::vector<std::uint16_t> ours = decodeBC6HHalf(blocks, width, height);
        const std::vector<std::uint16_t> driver = driverDecode(blocks, width, height);
        for (std::size_t i = 0; i < ours.size() && mismatches < 10; ++i)
            if (ours[i] != driver[i]) {
                const std::size_t texel = i / 3, x = texel % width, y = texel / width;
                const std::size_t block = (y / 4) * (width / 4) + x / 4;
                ADD_FAILURE() << "round " << round << " block " << block << " (mode 0x" << std::hex
                              << modes[block % modes.size()] << std::dec << ") texel " << x % 4
                              << "," << y % 4 << " channel " << i % 3 << ": ours 0x" << std::hex
                              << ours[i] << ", the driver's 0x" << driver[i];
                ++mismatches;
            }
    }
}

TEST_F(Bc6hGl, TheEncodersBlocksReadBackFromTheDriverAtTheQualityFloor) {
    const Image src = test::hdrTestImage(128, 64, 3);
    const std::vector<std::uint8_t> blocks = encodeBC6H(src);
    const std::vector<std::uint16_t> driver = driverDecode(blocks, src.width, src.height);
    EXPECT_EQ(driver, decodeBC6HHalf(blocks, src.width, src.height));
    Image back(src.width, src.height, 3);
    for (std::size_t i = 0; i < driver.size(); ++i)
        back.pixels[i] = glm::unpackHalf1x16(driver[i]);
    const double logPsnr = test::logLuminancePsnr(src, back), lin = test::linearPsnr(src, back);
    std::printf("[bc6h-gl] %s: log-luminance PSNR %.2f dB, linear PSNR %.2f dB\n",
                reinterpret_cast<const char*>(glGetString(GL_RENDERER)), logPsnr, lin);
    EXPECT_GE(logPsnr, 48.0);
    EXPECT_GE(lin, 45.0);
}

} // namespace
} // namespace specula
