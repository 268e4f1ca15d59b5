// libFuzzer target: the runtime's KTX 2.0 reader (parseKtx2, what every cooked texture goes
// through) on arbitrary bytes, unrestricted and with the exact-size limits a probe layer is read
// with. Any specula::Error is the expected refusal; anything else escaping, a crash or a
// sanitizer report is a finding. Seeds: the committed probe's layers
// (tests/fuzz/data/probe/*.ktx2, face-res 2) and tests/fuzz/corpus/ktx2/ (BC6H files).
//
// The unrestricted read is capped at 2^22 values (a 1024^2 RGBA image): a header may declare
// any size, and an allocation past the cap means a limit was not checked before the pixels.
#include "engine/core/error.h"
#include "engine/image/ktx2.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    try {
        (void)specula::parseKtx2(bytes, "input.ktx2", {.maxValues = 1ull << 22});
    } catch (const specula::Error&) {
    }
    try {
        (void)specula::parseKtx2(bytes, "input.ktx2",
                                 {.width = 2, .height = 2, .faces = 6, .channels = 4});
    } catch (const specula::Error&) {
    }
    return 0;
}
