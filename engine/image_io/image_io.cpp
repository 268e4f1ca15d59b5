#include "engine/image_io/image_io.h"

#include "engine/core/error.h"
#include "engine/core/file_write.h"
#include "engine/core/regular_file.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <system_error>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <unistd.h>

namespace specula {

namespace {

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    if (!ext.empty() && ext[0] == '.') ext.erase(0, 1);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

bool is8BitFormat(const std::string& ext) {
    return ext == "png" || ext == "jpg" || ext == "jpeg";
}

// Integer pixel data is display-encoded unless the file says otherwise; float data is
// scene-linear by convention (EXR, HDR).
bool defaultSrgb(const OIIO::ImageSpec& spec) {
    if (spec.format.is_floating_point()) return false;
    std::string cs = spec.get_string_attribute("oiio:ColorSpace");
    std::transform(cs.begin(), cs.end(), cs.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return cs.find("linear") == std::string::npos;
}

// Reads the first subimage of an opened input; returns an empty Image on failure and
// leaves the reason in `error`.
Image readOpened(OIIO::ImageInput& in, std::optional<bool> srgbToLinear,
                 const ImageReadLimits& limits, std::string& error) {
    const OIIO::ImageSpec& spec = in.spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
        error = "image has no pixels";
        return {};
    }
    const int channels = std::min(spec.nchannels, 4);
    if (std::uint64_t(spec.width) * std::uint64_t(spec.height) * std::uint64_t(channels) >
        limits.maxValues) {
        error = "image too large: " + std::to_string(spec.width) + " x " +
                std::to_string(spec.height) + " x " + std::to_string(channels) +
                " values, more than the " + std::to_string(limits.maxValues) + " this reader holds";
        return {};
    }
    Image img(spec.width, spec.height, channels);
    if (!in.read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, img.pixels.data())) {
        error = in.geterror();
        if (error.empty()) error = "cannot decode pixels";
        return {};
    }
    if (srgbToLinear.value_or(defaultSrgb(spec))) {
        const int alpha = spec.alpha_channel;
        for (std::size_t i = 0; i < img.pixels.size(); ++i) {
            if (int(i % std::size_t(channels)) == alpha) continue;
            img.pixels[i] = srgbToLinearValue(img.pixels[i]);
        }
    }
    return img;
}

// The channel layout a format can store: HDR is RGB only, JPEG grey or RGB.
int storedChannels(const std::string& ext, int channels) {
    if (ext == "hdr" || ext == "rgbe") return 3;
    if (ext == "jpg" || ext == "jpeg") return channels == 1 ? 1 : 3;
    return channels;
}

// Repacks to `outChannels`: grey is replicated into RGB, alpha dropped where not stored.
std::vector<float> repack(const Image& img, int outChannels) {
    std::vector<float> out(std::size_t(img.width) * img.height * outChannels);
    for (int y = 0; y < img.height; ++y) {
        for (int x = 0; x < img.width; ++x) {
            const float* src = img.at(x, y);
            float* dst = &out[(std::size_t(y) * img.width + x) * outChannels];
            for (int c = 0; c < outChannels; ++c) {
                if (img.channels >= 3 || outChannels == img.channels)
                    dst[c] = c < img.channels ? src[c] : 1.f;
                else // grey (+alpha) into RGB
                    dst[c] = src[0];
            }
        }
    }
    return out;
}

// Straight (unassociated) alpha in memory, as glTF textures are; without this OIIO would
// premultiply PNG colour on read and divide on write.
OIIO::ImageSpec readConfig() {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    return config;
}

} // namespace

namespace {

// Image files are bounded only so that a size is never absurd: a face-res 8192 probe layer
// (N x 6N float RGBA) is 6.4 GB.
constexpr std::uint64_t kMaxImageFileBytes = 16ull << 30;

// OpenEXR allocates each header attribute at the size it declares before reading it (a fuzzed
// 448-byte file declared a 1.9 GB string): every attribute's size is checked against the
// bytes the file holds first. Only sizes are checked; OpenEXR judges everything else, and a
// header cut short is left to it.
void checkExrAttributeSizes(const std::string& path, std::uint64_t fileBytes) {
    std::ifstream in(path, std::ios::binary);
    unsigned char start[8];
    if (!in.read(reinterpret_cast<char*>(start), 8)) return;
    if (start[0] != 0x76 || start[1] != 0x2f || start[2] != 0x31 || start[3] != 0x01) return;
    const bool multipart = (start[5] & 0x10) != 0; // version bit 12
    // A null-terminated name of at most 255 characters; nullopt when cut short or longer.
    const auto name = [&]() -> std::optional<std::string> {
        std::string text;
        for (char c; in.get(c);) {
            if (c == '\0') return text;
            if (text.size() == 255) return std::nullopt;
            text += c;
        }
        return std::nullopt;
    };
    for (int header = 0; header < 100000; ++header) {
        for (;;) {
            const std::optional<std::string> attribute = name();
            if (!attribute) return;
            if (attribute->empty()) break; // the header's end
            const std::optional<std::string> type = name();
            std::int32_t size = 0;
            if (!type || !in.read(reinterpret_cast<char*>(&size), 4)) return;
            const std::uint64_t at = std::uint64_t(in.tellg());
            if (size < 0 || at + std::uint64_t(size) > fileBytes)
                throw Error(path, "header",
                            "attribute '" + *attribute + "' declares " + std::to_string(size) +
                                " bytes; the file holds " + std::to_string(fileBytes) +
                                " (a damaged OpenEXR header)");
            in.seekg(std::streamoff(size), std::ios::cur);
        }
        // Multi-part: the headers follow each other, an empty one ends them.
        if (!multipart || in.peek() == 0 || !in) return;
    }
}

// Opens an image file for reading; a path that is not a regular file is refused first (OIIO
// would block on a FIFO and read a device forever).
std::unique_ptr<OIIO::ImageInput> openImage(const std::string& path) {
    checkExrAttributeSizes(path, regularFileSize(path, kMaxImageFileBytes));
    const OIIO::ImageSpec config = readConfig();
    auto in = OIIO::ImageInput::open(path, &config);
    if (!in) throw Error(path, "", "cannot read image: " + OIIO::geterror());
    return in;
}

Image readAndClose(OIIO::ImageInput& in, const std::string& path, std::optional<bool> srgbToLinear,
                   const ImageReadLimits& limits) {
    std::string error;
    Image img = readOpened(in, srgbToLinear, limits, error);
    in.close();
    if (img.empty()) throw Error(path, "", "cannot read image: " + error);
    return img;
}

} // namespace

Image readImage(const std::string& path, std::optional<bool> srgbToLinear,
                const ImageReadLimits& limits) {
    auto in = openImage(path);
    return readAndClose(*in, path, srgbToLinear, limits);
}

Image readFloatExr(const std::string& path, const ImageReadLimits& limits) {
    auto in = openImage(path);
    const std::string format = in->format_name();
    if (format != "openexr")
        throw Error(path, "format", "expected an OpenEXR file, found " + format + " data");
    const OIIO::ImageSpec& spec = in->spec();
    for (int c = 0; c < spec.nchannels; ++c) {
        const OIIO::TypeDesc t = spec.channelformat(c);
        if (t != OIIO::TypeDesc::FLOAT && t != OIIO::TypeDesc::HALF)
            throw Error(path, "channels",
                        "expected float or half channels, channel " + std::to_string(c) + " is " +
                            t.c_str());
    }
    if ((limits.width > 0 && spec.width != limits.width) ||
        (limits.height > 0 && spec.height != limits.height))
        throw Error(path, "size",
                    "expected " + std::to_string(limits.width) + " x " +
                        std::to_string(limits.height) + ", the header declares " +
                        std::to_string(spec.width) + " x " + std::to_string(spec.height));
    return readAndClose(*in, path, false, limits);
}

void writeImage(const std::string& path, const Image& image, const ImageWriteOptions& options) {
    if (image.empty() || image.width <= 0 || image.height <= 0 || image.channels <= 0 ||
        image.pixels.size() != std::size_t(image.width) * image.height * image.channels)
        throw Error(path, "", "cannot write an empty or inconsistent image");

    const std::string ext = lowerExtension(path);
    // Encoded in memory, then written by writeFileAtomically: OIIO's writers (PNG at least)
    // do not report a short write, and a full disk must never pass as a finished image.
    std::vector<unsigned char> encoded;
    OIIO::Filesystem::IOVecOutput memory(encoded);
    auto out = OIIO::ImageOutput::create(path, &memory);
    if (!out) throw Error(path, "", "no image writer for this extension: " + OIIO::geterror());
    if (!out->supports("ioproxy"))
        throw Error(path, "", "the " + ext + " writer cannot encode to memory (checked writes)");

    const int channels = storedChannels(ext, image.channels);
    std::vector<float> data = repack(image, channels);
    const bool eightBit = is8BitFormat(ext);
    OIIO::TypeDesc fileType = OIIO::TypeDesc::FLOAT;
    if (eightBit)
        fileType = OIIO::TypeDesc::UINT8;
    else if (ext == "exr" && options.halfFloat)
        fileType = OIIO::TypeDesc::HALF;

    OIIO::ImageSpec spec(image.width, image.height, channels, fileType);
    // OIIO stamps EXRs with the wall-clock time unless DateTime is set; empty leaves it out, so
    // the same pixels give the same bytes (cooked assets are compared and hashed by bytes).
    spec.attribute("DateTime", "");
    if (channels == 2 || channels == 4) {
        spec.alpha_channel = channels - 1;
        spec.attribute("oiio:UnassociatedAlpha", 1);
    }
    std::vector<std::uint8_t> bytes;
    const void* pixels = data.data();
    OIIO::TypeDesc memType = OIIO::TypeDesc::FLOAT;
    if (eightBit) {
        spec.attribute("oiio:ColorSpace", "sRGB");
        if (ext != "png") spec.attribute("CompressionQuality", options.jpegQuality);
        bytes.resize(data.size());
        for (std::size_t i = 0; i < data.size(); ++i) {
            const bool alpha = int(i % std::size_t(channels)) == spec.alpha_channel;
            const float v = alpha ? data[i] : linearToSrgbValue(data[i]);
            const float c = std::isnan(v) ? 0.f : std::clamp(v, 0.f, 1.f);
            bytes[i] = std::uint8_t(std::lround(c * 255.f));
        }
        pixels = bytes.data();
        memType = OIIO::TypeDesc::UINT8;
    }

    auto fail = [&](const std::string& why) {
        throw Error(path, "", "cannot encode image: " + why);
    };
    if (!out->open(path, spec)) fail(out->geterror());
    if (!out->write_image(memType, pixels)) {
        const std::string why = out->geterror();
        out->close();
        fail(why);
    }
    if (!out->close()) fail(out->geterror());
    writeFileAtomically(
        path, std::string_view(reinterpret_cast<const char*>(encoded.data()), encoded.size()));
}

std::optional<Image> decodeImageFromMemory(const void* data, std::size_t size,
                                           const std::string& formatHint,
                                           std::optional<bool> srgbToLinear) {
    if (!data || size == 0) return std::nullopt;
    const auto* b = static_cast<const unsigned char*>(data);
    auto startsWith = [&](const char* sig, std::size_t n) {
        return size >= n && std::memcmp(b, sig, n) == 0;
    };
    // OIIO picks its reader by file extension, so name the bytes by their signature first.
    std::string ext;
    if (startsWith("\x89PNG", 4))
        ext = "png";
    else if (startsWith("\xFF\xD8\xFF", 3))
        ext = "jpg";
    else if (startsWith("\x76\x2F\x31\x01", 4))
        ext = "exr";
    else if (startsWith("#?RADIANCE", 10) || startsWith("#?RGBE", 6))
        ext = "hdr";
    else {
        ext = formatHint;
        std::transform(ext.begin(), ext.end(), ext.begin(),
                       [](unsigned char c) { return char(std::tolower(c)); });
        if (const auto slash = ext.find('/'); slash != std::string::npos) ext.erase(0, slash + 1);
        if (!ext.empty() && ext[0] == '.') ext.erase(0, 1);
        if (ext == "jpeg") ext = "jpg";
        if (ext.empty()) return std::nullopt;
    }
    OIIO::Filesystem::IOMemReader reader(data, size);
    // OIIO 2.4's readers take the proxy from the open() configuration, not from create().
    OIIO::ImageSpec config = readConfig();
    void* proxy = &reader;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    const std::string name = "memory." + ext;
    auto in = OIIO::ImageInput::create(name, false, &config, &reader);
    OIIO::ImageSpec opened;
    if (!in || !in->open(name, opened, config)) {
        if (in) (void)in->geterror();
        (void)OIIO::geterror(); // consume, so it does not surface in a later unrelated call
        return std::nullopt;
    }
    std::string error;
    Image img = readOpened(*in, srgbToLinear, ImageReadLimits{}, error);
    in->close();
    if (img.empty()) return std::nullopt;
    return img;
}

} // namespace specula
