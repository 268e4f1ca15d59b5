// libFuzzer target: the cooked-probe manifest parser (ParsedManifest::parse, readDistanceProbe) on
// arbitrary text. The manifest "lives" in SPECULA_FUZZ_PROBE_DIR, a small cooked probe whose images
// exist, so inputs that keep a layer's file name and checksum reach the image reader too. Any
// specula::Error is the expected refusal; anything else is a finding.
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "engine/core/error.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const auto parsed = specula::ParsedManifest::parse(
            text, std::string(SPECULA_FUZZ_PROBE_DIR) + "/manifest.json");
        (void)specula::readDistanceProbe(parsed.view());
    } catch (const specula::Error&) {
    }
    return 0;
}
