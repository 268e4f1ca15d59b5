#pragma once
// Image files through OpenImageIO. Images in memory are always linear float; the 8-bit
// formats (PNG, JPG) are sRGB-encoded on disk, so reading decodes and writing encodes.
#include "engine/image/image.h"
#include "engine/image/srgb.h" // the transfer function every 8-bit read and write applies

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace specula {

// What a read may allocate, checked against the file's header before any pixel is decoded: a
// header can declare any size (a constant 10^5 x 10^5 EXR compresses to a few bytes).
struct ImageReadLimits {
    // width x height x channels read; the default admits a face-res 8192 probe layer.
    std::uint64_t maxValues = 1ull << 31;
    // When > 0, the header must declare exactly this size (a probe layer's is in its manifest).
    int width = 0;
    int height = 0;
};

// Reads any format OIIO knows. srgbToLinear: decode the colour channels (never alpha) from
// sRGB; when not given, true for integer pixel formats (PNG, JPG, ...) and false for float
// ones (EXR, HDR). Throws Error naming the file when it cannot be read.
// Only a regular file is opened: a FIFO, device or directory is refused before OIIO sees it.
Image readImage(const std::string& path, std::optional<bool> srgbToLinear = std::nullopt,
                const ImageReadLimits& limits = {});

// readImage for the files a cooked probe stores: the file must really be OpenEXR (a PNG
// renamed .exr is refused, field "format") with float or half channels (field "channels");
// the pixels are read as they are, linear. A size other than the limits' (field "size") is
// refused before the pixels are allocated.
Image readFloatExr(const std::string& path, const ImageReadLimits& limits = {});

struct ImageWriteOptions {
    bool halfFloat = false; // EXR only: store half instead of float
    int jpegQuality = 95;
};

// Writes by extension: .exr (float or half), .hdr (RGB), .png (8-bit, alpha kept), .jpg
// (8-bit RGB). 8-bit formats get the colour channels clamped and sRGB-encoded. The file
// appears atomically: encoded in memory, written next to the target under a temporary name
// with every write checked (a full disk is an error, never a truncated image), then renamed.
// Throws Error naming the file on failure.
void writeImage(const std::string& path, const Image& image, const ImageWriteOptions& options = {});

// Decodes an encoded image (PNG, JPG, EXR, HDR, ...) held in memory, e.g. one embedded in a
// glTF buffer. formatHint: a file extension or MIME type ("png", "image/jpeg") used when
// the bytes' signature is not recognised. Returns nullopt when it cannot be decoded.
std::optional<Image> decodeImageFromMemory(const void* data, std::size_t size,
                                           const std::string& formatHint = "",
                                           std::optional<bool> srgbToLinear = std::nullopt);

} // namespace specula
