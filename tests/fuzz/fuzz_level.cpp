// libFuzzer target: a baked level's index reader (levelIndexFromJson, what every loader of a
// level runs on DIR/level.json) on arbitrary text. Text that is no JSON is the JSON parser's
// refusal (ParsedManifest's); any specula::Error is the expected refusal of the rest; anything
// else escaping (a nlohmann type_error from an unchecked member, say), a crash or a sanitizer
// report is a finding. Seeds: tests/fuzz/corpus/level/ (indexes the cooker wrote).
#include "components/reflection_probe/level_index.h"
#include "engine/core/error.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
    if (j.is_discarded()) return 0;
    try {
        (void)specula::levelIndexFromJson(j, "level.json");
    } catch (const specula::Error&) {
    }
    return 0;
}
