#include "engine/image_io/contact_sheet.h"

#include <gtest/gtest.h>

namespace specula {
namespace {

Image solid(int w, int h, float r, float g, float b) {
    Image img(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            img.at(x, y)[0] = r;
            img.at(x, y)[1] = g;
            img.at(x, y)[2] = b;
        }
    return img;
}

TEST(ContactSheet, LaysTilesOutInAGrid) {
    const std::vector<Image> tiles{solid(40, 20, 1, 0, 0), solid(80, 40, 0, 1, 0),
                                   solid(20, 10, 0, 0, 1)};
    const Image sheet = contactSheet(tiles, {"red", "green", "blue"}, 2, 64);
    ASSERT_EQ(sheet.channels, 3);
    EXPECT_GT(sheet.width, 2 * 64);
    EXPECT_LT(sheet.width, 2 * 64 + 40);
    // Two rows of 32-pixel-high tiles plus gaps and labels.
    EXPECT_GT(sheet.height, 2 * 32);
    // Cell centres hold the tile colours, in reading order.
    const int gapGuess = (sheet.width - 2 * 64) / 3;
    const glm::vec4 first = sheet.rgba(gapGuess + 32, gapGuess + 16);
    const glm::vec4 second = sheet.rgba(2 * gapGuess + 64 + 32, gapGuess + 16);
    EXPECT_NEAR(first.r, 1.f, 1e-3f);
    EXPECT_NEAR(first.g, 0.f, 1e-3f);
    EXPECT_NEAR(second.g, 1.f, 1e-3f);
    EXPECT_NEAR(second.r, 0.f, 1e-3f);
}

TEST(ContactSheet, LabelsDrawTextWhenAFontExists) {
    if (!contactSheetHasFont()) GTEST_SKIP() << "no font for OpenImageIO on this machine";
    const std::vector<Image> tiles{solid(64, 32, 0, 0, 0)};
    const Image plain = contactSheet(tiles, {""}, 1, 64);
    const Image labelled = contactSheet(tiles, {"Specula"}, 1, 64);
    float brightest = 0.f;
    for (float v : labelled.pixels)
        brightest = std::max(brightest, v);
    EXPECT_GT(brightest, 0.5f);
    EXPECT_GT(labelled.height, plain.height);
}

TEST(Hconcat, PlacesImagesSideBySide) {
    const Image out = hconcat({solid(3, 2, 1, 0, 0), solid(2, 4, 0, 1, 0)}, 1);
    ASSERT_EQ(out.width, 6);
    ASSERT_EQ(out.height, 4);
    EXPECT_EQ(out.at(0, 0)[0], 1.f);
    EXPECT_EQ(out.at(4, 3)[1], 1.f);
    EXPECT_NE(out.at(3, 0)[0], 1.f); // the gap
}

} // namespace
} // namespace specula
