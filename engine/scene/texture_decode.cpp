#include "texture_decode.h"

#include <array>
#include <climits>
#include <cmath>
#include <memory>

// stb_image compiled privately (static functions) so that it cannot clash with another
// copy in the program; only the two formats glTF allows, to keep the attack surface small.
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_NO_STDIO
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wall"
#pragma GCC diagnostic ignored "-Wextra"
#pragma GCC diagnostic ignored "-Wpedantic"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#pragma GCC diagnostic ignored "-Wunused-but-set-variable"
#endif
#include <stb/stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace specula {

namespace {
const std::array<float, 256>& srgbTable() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) {
            const double c = i / 255.0;
            t[std::size_t(i)] =
                float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
        }
        return t;
    }();
    return table;
}
} // namespace

float srgb8ToLinear(unsigned char code) {
    return srgbTable()[code];
}

std::optional<Image> decodeTexture8(const unsigned char* bytes, std::size_t size, bool srgb,
                                    std::string& whyNot) {
    if (bytes == nullptr || size == 0) {
        whyNot = "no image data";
        return std::nullopt;
    }
    if (size > std::size_t(INT_MAX)) {
        whyNot = "encoded image larger than 2 GiB";
        return std::nullopt;
    }
    int w = 0, h = 0, channelsInFile = 0;
    std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
        stbi_load_from_memory(bytes, int(size), &w, &h, &channelsInFile, 4), stbi_image_free);
    if (!pixels) {
        const char* reason = stbi_failure_reason();
        whyNot = std::string("not a decodable PNG or JPEG (") + (reason ? reason : "unknown") + ")";
        return std::nullopt;
    }
    Image image(w, h, 4);
    const std::size_t n = std::size_t(w) * std::size_t(h) * 4;
    for (std::size_t i = 0; i < n; ++i) {
        const bool alpha = (i % 4) == 3;
        image.pixels[i] =
            (srgb && !alpha) ? srgb8ToLinear(pixels.get()[i]) : float(pixels.get()[i]) / 255.f;
    }
    return image;
}

} // namespace specula
