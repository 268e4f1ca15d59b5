#include "engine/image_io/contact_sheet.h"

#include "engine/core/error.h"

#include <algorithm>
#include <array>
#include <filesystem>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

namespace specula {

namespace {

constexpr int kGap = 6;
constexpr float kBackground = 0.02f;

// OIIO's default font (DroidSans) is not packaged on Debian, so name a font file
// explicitly. Empty when none is present.
const std::string& labelFont() {
    static const std::string font = [] {
        static constexpr std::array<const char*, 4> candidates{
            "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
            "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
            "/usr/share/fonts/truetype/freefont/FreeSans.ttf",
            "/usr/share/fonts/TTF/DejaVuSans.ttf"};
        for (const char* c : candidates) {
            std::error_code ec;
            if (std::filesystem::is_regular_file(c, ec)) return std::string(c);
        }
        return std::string();
    }();
    return font;
}

OIIO::ImageBuf toRgbBuf(const Image& img) {
    OIIO::ImageBuf buf(OIIO::ImageSpec(img.width, img.height, 3, OIIO::TypeDesc::FLOAT));
    std::vector<float> data(std::size_t(img.width) * img.height * 3);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const glm::vec4 c = img.channels >= 3 ? img.rgba(x, y) : glm::vec4(img.at(x, y)[0]);
            float* d = &data[(std::size_t(y) * img.width + x) * 3];
            d[0] = c.r;
            d[1] = c.g;
            d[2] = c.b;
        }
    buf.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, data.data());
    return buf;
}

} // namespace

bool contactSheetHasFont() {
    return !labelFont().empty();
}

Image contactSheet(const std::vector<Image>& tiles, const std::vector<std::string>& labels,
                   int columns, int tileWidth) {
    if (columns <= 0) throw Error("", "columns", "contact sheet needs at least one column");
    if (tileWidth <= 0) throw Error("", "tileWidth", "contact sheet needs a positive tile width");
    if (tiles.empty()) return Image(1, 1, 3);

    std::vector<OIIO::ImageBuf> resized(tiles.size());
    int cellHeight = 1;
    for (std::size_t i = 0; i < tiles.size(); ++i) {
        const Image& t = tiles[i];
        if (t.empty() || t.width <= 0 || t.height <= 0) continue;
        const int h = std::max(1, int(std::lround(double(tileWidth) * t.height / t.width)));
        OIIO::ImageBuf src = toRgbBuf(t);
        OIIO::ImageBuf dst(OIIO::ImageSpec(tileWidth, h, 3, OIIO::TypeDesc::FLOAT));
        if (!OIIO::ImageBufAlgo::resize(dst, src))
            throw Error("", "tiles", "cannot resize tile: " + dst.geterror());
        resized[i] = std::move(dst);
        cellHeight = std::max(cellHeight, h);
    }

    const bool anyLabel =
        std::any_of(labels.begin(), labels.end(), [](const std::string& l) { return !l.empty(); });
    const int fontSize = std::clamp(tileWidth / 14, 10, 22);
    const int labelHeight = anyLabel ? fontSize + fontSize / 2 : 0;
    const int count = int(tiles.size());
    const int cols = std::min(columns, count);
    const int rows = (count + cols - 1) / cols;
    const int width = kGap + cols * (tileWidth + kGap);
    const int height = kGap + rows * (cellHeight + labelHeight + kGap);

    OIIO::ImageBuf sheet(OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::FLOAT));
    const float bg[3] = {kBackground, kBackground, kBackground};
    OIIO::ImageBufAlgo::fill(sheet, bg);
    const std::string& font = labelFont();
    for (int i = 0; i < count; ++i) {
        const int x0 = kGap + (i % cols) * (tileWidth + kGap);
        const int y0 = kGap + (i / cols) * (cellHeight + labelHeight + kGap);
        if (resized[std::size_t(i)].initialized())
            OIIO::ImageBufAlgo::paste(sheet, x0, y0, 0, 0, resized[std::size_t(i)]);
        if (std::size_t(i) < labels.size() && !labels[std::size_t(i)].empty() && !font.empty()) {
            const float white[3] = {0.9f, 0.9f, 0.9f};
            // A missing glyph or a broken font only costs the label, never the sheet.
            if (!OIIO::ImageBufAlgo::render_text(sheet, x0 + 2, y0 + cellHeight + fontSize,
                                                 labels[std::size_t(i)], fontSize, font, white))
                (void)sheet.geterror();
        }
    }

    Image out(width, height, 3);
    sheet.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, out.pixels.data());
    return out;
}

Image hconcat(const std::vector<Image>& images, int gap) {
    gap = std::max(gap, 0);
    int width = 0, height = 0, channels = 1;
    for (const Image& img : images) {
        if (img.empty()) continue;
        if (width > 0) width += gap;
        width += img.width;
        height = std::max(height, img.height);
        channels = std::max(channels, img.channels);
    }
    if (width == 0 || height == 0) return {};
    Image out(width, height, channels);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            float* p = out.at(x, y);
            for (int c = 0; c < channels; ++c)
                p[c] = (c == 3) ? 1.f : kBackground;
        }
    int x0 = 0;
    for (const Image& img : images) {
        if (img.empty()) continue;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) {
                const glm::vec4 v = img.rgba(x, y);
                float* p = out.at(x0 + x, y);
                for (int c = 0; c < channels; ++c)
                    p[c] = (img.channels == 1 && c < 3) ? v.r : v[c];
            }
        x0 += img.width + gap;
    }
    return out;
}

} // namespace specula
