// libFuzzer target: the glTF/GLB loader (Draco included) on arbitrary bytes. The input is
// written to a private temporary file (.glb when it starts with the GLB magic, else .gltf)
// because loadGltf reads from a path. Any specula::Error is the expected way to refuse
// input; anything else escaping, a crash or a sanitizer report is a finding.
#include "engine/core/error.h"
#include "engine/ecs/registry.h"
#include "engine/scene/gltf_loader.h"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace {

const std::filesystem::path& scratchDir() {
    static const std::filesystem::path dir = [] {
        auto d = std::filesystem::temp_directory_path() /
                 ("specula-fuzz-gltf-" + std::to_string(::getpid()));
        std::filesystem::create_directories(d);
        return d;
    }();
    return dir;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const bool glb =
        size >= 4 && data[0] == 'g' && data[1] == 'l' && data[2] == 'T' && data[3] == 'F';
    const std::filesystem::path path = scratchDir() / (glb ? "input.glb" : "input.gltf");
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    }
    try {
        specula::ecs::Registry registry;
        (void)specula::loadGltf(path.string(), registry);
    } catch (const specula::Error&) {
        // Refused with a message naming the file: what bad input must get.
    }
    return 0;
}
