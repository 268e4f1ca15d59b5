#include "engine/core/error.h"
#include "engine/image_io/image_io.h"
#include "numerics/bad_input_support.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

namespace specula {
namespace {

class ImageIoTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() /
               ("specula_image_io_" + std::to_string(::getpid()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    std::filesystem::path dir_;
};

Image gradient(int w, int h, int channels) {
    Image img(w, h, channels);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < channels; ++c)
                img.at(x, y)[c] = float(x + 3 * y + 7 * c) / float(w + 3 * h + 7 * channels);
    return img;
}

TEST_F(ImageIoTest, ExrRoundTripIsExact) {
    Image img = gradient(13, 7, 4);
    img.at(2, 3)[0] = 1234.5f; // HDR values survive
    img.at(4, 1)[2] = -0.25f;
    writeImage(path("a.exr"), img);
    const Image back = readImage(path("a.exr"));
    ASSERT_EQ(back.width, img.width);
    ASSERT_EQ(back.height, img.height);
    ASSERT_EQ(back.channels, img.channels);
    EXPECT_EQ(back.pixels, img.pixels);
}

TEST_F(ImageIoTest, ExrHeaderHoldsNoWallClockTime) {
    // Cooked assets are hashed and compared by bytes: the same pixels must give the same file.
    // OpenImageIO otherwise writes a "DateTime" attribute (plain ASCII in the EXR header).
    writeImage(path("t.exr"), gradient(5, 4, 3));
    std::ifstream in(path("t.exr"), std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    ASSERT_FALSE(bytes.empty());
    EXPECT_EQ(bytes.find("DateTime"), std::string::npos);
}

TEST_F(ImageIoTest, ExrHalfIsCloseAndRowZeroStaysOnTop) {
    Image img(4, 3, 3);
    img.at(0, 0)[0] = 1.f; // top-left red
    writeImage(path("h.exr"), img, ImageWriteOptions{.halfFloat = true});
    const Image back = readImage(path("h.exr"));
    EXPECT_EQ(back.at(0, 0)[0], 1.f);
    EXPECT_EQ(back.at(0, 2)[0], 0.f);
}

TEST_F(ImageIoTest, PngSrgbRoundTripWithinOneStep) {
    const Image img = gradient(32, 8, 4);
    writeImage(path("a.png"), img);
    const Image back = readImage(path("a.png"));
    ASSERT_EQ(back.channels, 4);
    ASSERT_EQ(back.pixels.size(), img.pixels.size());
    for (std::size_t i = 0; i < img.pixels.size(); ++i) {
        const bool alpha = i % 4 == 3;
        // One 8-bit step of the stored (encoded) value; half a step from rounding.
        const float a = alpha ? img.pixels[i] : linearToSrgbValue(img.pixels[i]);
        const float b = alpha ? back.pixels[i] : linearToSrgbValue(back.pixels[i]);
        EXPECT_NEAR(a, b, 0.5f / 255.f + 1e-5f) << "value " << i;
    }
}

TEST_F(ImageIoTest, PngIsSrgbEncodedOnDisk) {
    Image img(1, 1, 3);
    img.at(0, 0)[0] = 0.5f; // linear mid grey encodes to 188/255
    writeImage(path("g.png"), img);
    const Image raw = readImage(path("g.png"), false);
    EXPECT_NEAR(raw.at(0, 0)[0], 188.f / 255.f, 1e-6f);
    EXPECT_NEAR(readImage(path("g.png")).at(0, 0)[0], 0.5f, 0.003f);
}

TEST_F(ImageIoTest, PngClampsOutOfRangeValues) {
    Image img(2, 1, 3);
    img.at(0, 0)[0] = 7.f;
    img.at(1, 0)[0] = -1.f;
    writeImage(path("c.png"), img);
    const Image back = readImage(path("c.png"));
    EXPECT_FLOAT_EQ(back.at(0, 0)[0], 1.f);
    EXPECT_FLOAT_EQ(back.at(1, 0)[0], 0.f);
}

TEST_F(ImageIoTest, HdrAndJpgWriteRgb) {
    const Image img = gradient(8, 8, 4);
    writeImage(path("a.hdr"), img);
    const Image hdr = readImage(path("a.hdr"));
    ASSERT_EQ(hdr.channels, 3);
    EXPECT_NEAR(hdr.at(5, 6)[1], img.at(5, 6)[1], 0.01f);
    writeImage(path("a.jpg"), img);
    const Image jpg = readImage(path("a.jpg"));
    ASSERT_EQ(jpg.channels, 3);
    EXPECT_NEAR(jpg.at(5, 6)[1], img.at(5, 6)[1], 0.05f);
}

TEST_F(ImageIoTest, ReadingAMissingFileNamesIt) {
    const std::string missing = path("does_not_exist.exr");
    try {
        (void)readImage(missing);
        FAIL() << "expected an Error";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), missing);
        EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
    }
}

// Only regular files are opened: OIIO would block on a FIFO until a writer came and read a
// device without end.
TEST_F(ImageIoTest, ReadingAFifoIsRefusedWithoutBlocking) {
    const std::string fifo = path("pipe.exr");
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    test::expectNames(test::errorOfInChild([&] { (void)readImage(fifo); }), {fifo, "FIFO"});
}

TEST_F(ImageIoTest, ReadingADirectoryDeviceOrSymlinkLoopIsRefused) {
    std::filesystem::create_directory(path("dir.png"));
    test::expectNames(test::errorOf([&] { (void)readImage(path("dir.png")); }),
                      {path("dir.png"), "a directory"});
    std::filesystem::create_symlink("/dev/zero", path("zero.exr"));
    test::expectNames(test::errorOfInChild([&] { (void)readImage(path("zero.exr")); }),
                      {path("zero.exr"), "character device"});
    std::filesystem::create_symlink("loop.exr", path("loop.exr"));
    test::expectNames(test::errorOf([&] { (void)readImage(path("loop.exr")); }),
                      {path("loop.exr"), "symlink loop"});
}

TEST_F(ImageIoTest, ReadFloatExrReadsFloatAndHalf) {
    const Image img = gradient(5, 3, 4);
    writeImage(path("f.exr"), img);
    EXPECT_EQ(readFloatExr(path("f.exr")).pixels, img.pixels);
    writeImage(path("h.exr"), img, ImageWriteOptions{.halfFloat = true});
    EXPECT_NEAR(readFloatExr(path("h.exr")).at(4, 2)[3], img.at(4, 2)[3], 1e-3f);
}

TEST_F(ImageIoTest, ReadFloatExrRefusesAPngRenamedExr) {
    writeImage(path("p.png"), gradient(5, 3, 4));
    std::filesystem::rename(path("p.png"), path("p.exr"));
    EXPECT_EQ(readImage(path("p.exr")).width, 5); // readImage takes any format OIIO knows
    test::expectNames(test::errorOf([&] { (void)readFloatExr(path("p.exr")); }),
                      {path("p.exr"), "format", "OpenEXR", "png"});
}

// A header may declare any size; reading it must not try to allocate 160 GB.
// An attribute declaring more bytes than the file holds (what the fuzzer found: a 448-byte
// file whose 'capDate' string declared 1.9 GB, which OpenEXR allocated before reading) is
// refused naming the attribute, before OpenImageIO opens the file.
TEST_F(ImageIoTest, AnExrAttributeLargerThanItsFileIsRefusedBeforeAllocating) {
    writeImage(path("small.exr"), gradient(4, 4, 4));
    std::string bytes = test::slurp(path("small.exr"));
    const std::string attr = std::string("channels\0chlist\0", 16);
    const std::size_t at = bytes.find(attr);
    ASSERT_NE(at, std::string::npos);
    const std::int32_t declared = 1962934291;
    std::memcpy(&bytes[at + attr.size()], &declared, sizeof declared);
    test::spit(path("damaged.exr"), bytes);
    test::expectNames(test::errorOf([&] { (void)readImage(path("damaged.exr")); }),
                      {path("damaged.exr"), "header", "'channels' declares 1962934291 bytes"});
    EXPECT_EQ(readImage(path("small.exr")).width, 4); // an intact header reads as before
}

TEST_F(ImageIoTest, HugeDeclaredSizeIsRefusedBeforeAllocating) {
    writeImage(path("small.exr"), gradient(4, 4, 4));
    std::string bytes = test::slurp(path("small.exr"));
    const std::string attr = std::string("dataWindow\0box2i\0", 17);
    const std::size_t at = bytes.find(attr);
    ASSERT_NE(at, std::string::npos);
    const std::int32_t window[4] = {0, 0, 99999, 99999}; // after the 4-byte attribute size
    std::memcpy(&bytes[at + attr.size() + 4], window, sizeof window);
    // Room for the chunk-offset table the header implies (8 bytes a chunk, at most one chunk
    // a scanline), whatever compression the writer chose.
    bytes.append(8 * 100000 + 4096, '\0');
    test::spit(path("huge.exr"), bytes);
    test::expectNames(test::errorOf([&] { (void)readImage(path("huge.exr")); }),
                      {path("huge.exr"), "too large", "100000 x 100000"});
    // A probe layer is read at the size its manifest names: the forged header is refused by
    // size, and a tighter value limit refuses what the default would hold.
    test::expectNames(
        test::errorOf([&] { (void)readFloatExr(path("huge.exr"), {.width = 4, .height = 24}); }),
        {path("huge.exr"), "size", "4 x 24", "100000 x 100000"});
    writeImage(path("mid.exr"), gradient(64, 64, 4));
    test::expectNames(
        test::errorOf([&] { (void)readImage(path("mid.exr"), std::nullopt, {.maxValues = 4096}); }),
        {path("mid.exr"), "too large", "64 x 64 x 4"});
    EXPECT_EQ(readImage(path("mid.exr"), std::nullopt, {.maxValues = 64 * 64 * 4}).width, 64);
}

TEST_F(ImageIoTest, WriteIsAtomicAndLeavesNoTemporary) {
    writeImage(path("x.png"), gradient(4, 4, 3));
    int files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir_)) {
        ++files;
        EXPECT_EQ(entry.path().filename(), "x.png");
    }
    EXPECT_EQ(files, 1);
}

TEST_F(ImageIoTest, FailedWriteThrowsAndLeavesNothing) {
    EXPECT_THROW(writeImage(path("no_such_dir/x.exr"), gradient(4, 4, 3)), Error);
    EXPECT_THROW(writeImage(path("x.unknownformat"), gradient(4, 4, 3)), Error);
    EXPECT_THROW(writeImage(path("empty.exr"), Image()), Error);
    EXPECT_TRUE(std::filesystem::is_empty(dir_));
}

TEST_F(ImageIoTest, DecodesFromMemory) {
    const Image img = gradient(6, 5, 3);
    writeImage(path("m.png"), img);
    std::ifstream f(path("m.png"), std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    const auto decoded = decodeImageFromMemory(bytes.data(), bytes.size(), "image/png");
    ASSERT_TRUE(decoded.has_value());
    const Image fromFile = readImage(path("m.png"));
    EXPECT_EQ(decoded->pixels, fromFile.pixels);

    const std::string junk = "definitely not an image";
    EXPECT_FALSE(decodeImageFromMemory(junk.data(), junk.size(), "image/png").has_value());
    EXPECT_FALSE(decodeImageFromMemory(nullptr, 0).has_value());
}

TEST(SrgbTransfer, InvertsAndHitsKnownValues) {
    EXPECT_FLOAT_EQ(srgbToLinearValue(0.f), 0.f);
    EXPECT_FLOAT_EQ(srgbToLinearValue(1.f), 1.f);
    EXPECT_NEAR(linearToSrgbValue(0.18f), 0.4613f, 1e-4f);
    for (float v = 0.f; v <= 1.f; v += 0.01f)
        EXPECT_NEAR(srgbToLinearValue(linearToSrgbValue(v)), v, 1e-5f);
}

} // namespace
} // namespace specula
