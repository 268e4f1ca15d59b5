// libFuzzer target: the image loader a cooked probe's layers go through (readFloatExr, and
// readImage, which takes any format) on arbitrary bytes, written to a private temporary
// .exr file because the loader reads from a path. Any specula::Error is the expected
// refusal; anything else escaping, a crash or a sanitizer report is a finding. Seeds: the
// committed probe's layers (tests/fuzz/data/probe/*.exr, face-res 2) and
// tests/fuzz/corpus/exr/.
//
// Memory and time: a header may declare any size and the fuzzer runs under -rss_limit_mb=2048
// with ASan, where decoding 2^26 values takes ~12 s; so the harness reads with a limit of
// 2^22 values (a 1024^2 RGBA image) and lowers OIIO's own uncompressed-size limit to match; the
// probe loader's path is the exact-size read with the seeds' face-res (2 x 12), refused before
// allocation when the header differs. An allocation past these limits is a finding: it means a
// limit is not checked first.
#include "engine/core/error.h"
#include "engine/image_io/image_io.h"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include <OpenImageIO/imageio.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const bool limited = [] { return OIIO::attribute("limits:imagesize_MB", 32); }();
    (void)limited;
    static const std::filesystem::path path = [] {
        const auto dir = std::filesystem::temp_directory_path() /
                         ("specula-fuzz-exr-" + std::to_string(::getpid()));
        std::filesystem::create_directories(dir);
        return dir / "input.exr";
    }();
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    }
    const specula::ImageReadLimits any{.maxValues = 1ull << 22};
    const specula::ImageReadLimits layer{.maxValues = 1ull << 22, .width = 2, .height = 12};
    for (int reader = 0; reader < 3; ++reader) {
        try {
            if (reader == 0) (void)specula::readFloatExr(path.string(), layer);
            if (reader == 1) (void)specula::readFloatExr(path.string(), any);
            if (reader == 2) (void)specula::readImage(path.string(), std::nullopt, any);
        } catch (const specula::Error&) {
        }
    }
    return 0;
}
