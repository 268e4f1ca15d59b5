// libFuzzer target: the image loader a cooked probe's layers go through (readFloatExr, and
// readImage, which takes any format) on arbitrary bytes, written to a private temporary
// .exr file because the loader reads from a path. Any specula::Error is the expected
// refusal; anything else escaping, a crash or a sanitizer report is a finding. Seeds: the
// committed probe's layers (tests/fuzz/data/probe/*.exr) and tests/fuzz/corpus/exr/.
#include "engine/core/error.h"
#include "engine/image/image_io.h"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
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
    for (const bool exrOnly : {true, false}) {
        try {
            (void)(exrOnly ? specula::readFloatExr(path.string())
                           : specula::readImage(path.string()));
        } catch (const specula::Error&) {
        }
    }
    return 0;
}
