// libFuzzer target: the light-field rows reader (readLightFieldRows, a part shard a farm node
// wrote) on arbitrary bytes, expecting slab 1, camera row 0 of a 2 x 2-camera, 2^2-pixel
// probe (the seed corpus holds a valid one). The reader takes a file: each input is written
// to one per process first. Any specula::Error is the expected refusal; anything else is a
// finding.
#include "assetcooker/lib/flavours/lightfield/lightfield_rows.h"
#include "engine/core/error.h"

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

// The per-process input file, removed when the process ends.
struct InputFile {
    std::string path =
        (std::filesystem::temp_directory_path() / ("specula-fuzz-rows-" + std::to_string(getpid())))
            .string();
    ~InputFile() {
        std::error_code ec;
        std::filesystem::remove(path, ec);
    }
};

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const InputFile input;
    const std::string& file = input.path;
    {
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    }
    try {
        const specula::LightFieldRows rows = specula::readLightFieldRows(file, 1, 0, 1, 2, 2);
        (void)rows;
    } catch (const specula::Error&) {
    }
    return 0;
}
