// libFuzzer entry point: a farm's shard list reader (shardListFromJson, what bake-shard, merge
// and every dependent shard run on DIR/.shards/shards.json) on arbitrary text. Text that is no
// JSON is the JSON parser's refusal; any specula::Error is the expected refusal of the rest;
// anything else escaping (a nlohmann exception from an unchecked member), a crash or a
// sanitizer report is a finding. Seeds: tests/fuzz/corpus/shards/ (lists the cooker wrote for a
// distance level, a light-field level and a PEM, and damaged ones).
//
// It reads through the cooker's settings readers, so it is built as replay_shards in the
// ordinary build only (the libFuzzer build holds the runtime's readers, not the cooker).
#include "assetcooker/lib/farm/shard_bake.h"
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
        (void)specula::shardListFromJson(j, "shards.json");
    } catch (const specula::Error&) {
    }
    return 0;
}
