#include "assetcooker/lib/farm/shard_bake.h"

#include "assetcooker/lib/flavours/pem/shard_pem.h"

#include <filesystem>

// Where a shard list's shards lie in the store, which of them a bake still needs, and their
// names in reports (shard_bake.h).

namespace specula {

namespace fs = std::filesystem;

std::string shardStore(const std::string& dir) {
    return (fs::path(dir) / ".shards").string();
}

std::string shardListPath(const std::string& dir) {
    return (fs::path(shardStore(dir)) / "shards.json").string();
}

std::string shardTimePath(const std::string& dir, const Shard& s) {
    return (fs::path(shardStore(dir)) / (s.hash + ".time.json")).string();
}

std::string mergeTimePath(const std::string& dir) {
    return (fs::path(shardStore(dir)) / "merge.time.json").string();
}

std::string shardOutputPath(const std::string& dir, const Shard& s) {
    const fs::path store(shardStore(dir));
    const char* suffix = s.kind == kLightFieldRowsShard ? ".rows"
                         : s.kind == kPemTraceShard     ? ".trace"
                         : s.kind == kPemSampleShard    ? ".map"
                                                        : "";
    return (store / (s.hash + suffix)).string();
}

bool isFinalShard(const Shard& s) {
    return s.kind == kProbeShard || s.kind == kPemSampleShard;
}

std::vector<int> dependentShardsToBake(const std::string& dir, const ShardList& list) {
    std::vector<int> out;
    for (std::size_t i = 0; i < list.shards.size(); ++i)
        if (isFinalShard(list.shards[i]) && !shardPresent(dir, list.shards[i]) &&
            !shardDependencies(list, int(i)).empty())
            out.push_back(int(i));
    return out;
}

bool shardPresent(const std::string& dir, const Shard& s) {
    std::error_code ec;
    // A probe folder's manifest is the last file its writer renames in; a part's file is
    // renamed in whole.
    if (s.kind != kProbeShard) return fs::is_regular_file(shardOutputPath(dir, s), ec);
    return fs::is_regular_file(fs::path(shardOutputPath(dir, s)) / "manifest.json", ec);
}

std::vector<int> shardDependencies(const ShardList& list, int index) {
    std::vector<int> deps;
    const Shard& s = list.shards[std::size_t(index)];
    if (isPemList(list)) return pemShardDependencies(list, index);
    if (s.kind != kProbeShard) return deps;
    for (std::size_t i = 0; i < list.shards.size(); ++i)
        if (list.shards[i].kind == kLightFieldRowsShard && list.shards[i].probe == s.probe)
            deps.push_back(int(i));
    return deps;
}

std::vector<int> leafShardsToBake(const std::string& dir, const ShardList& list) {
    std::vector<bool> needed(list.shards.size(), false);
    for (std::size_t i = 0; i < list.shards.size(); ++i) {
        if (!isFinalShard(list.shards[i]) || shardPresent(dir, list.shards[i])) continue;
        const std::vector<int> deps = shardDependencies(list, int(i));
        if (deps.empty()) needed[i] = true;
        for (const int d : deps)
            if (!shardPresent(dir, list.shards[std::size_t(d)])) needed[std::size_t(d)] = true;
    }
    std::vector<int> out;
    for (std::size_t i = 0; i < needed.size(); ++i)
        if (needed[i]) out.push_back(int(i));
    return out;
}

std::string shardLabel(const ShardList& list, int index) {
    const Shard& s = list.shards[std::size_t(index)];
    if (s.kind == kPemTraceShard || s.kind == kPemSampleShard)
        return "PEM sample " + std::to_string(s.part) +
               (s.kind == kPemTraceShard ? ": trace" : ": maps");
    std::string label = "probe " + list.level.probes[std::size_t(s.probe)].volume.name;
    if (s.kind == kLightFieldRowsShard)
        label += ", part " + std::to_string(s.part) + ": slab " + std::to_string(s.slab) +
                 " rows " + std::to_string(s.j0) + " .. " + std::to_string(s.j1 - 1);
    return label;
}

std::string describeShards(const ShardList& list) {
    std::string text = std::to_string(list.shards.size()) + " shards";
    if (isPemList(list))
        return text + " (" + std::to_string(pemListSamples(list)) + " PEM trace shards + " +
               std::to_string(pemListSamples(list)) + " PEM sample shards)";
    if (list.shardRows > 0) {
        std::size_t parts = 0;
        for (const Shard& s : list.shards)
            parts += s.kind == kLightFieldRowsShard ? 1 : 0;
        text += " (" + std::to_string(parts) + " light-field part shards of " +
                std::to_string(list.shardRows) + " camera rows + " +
                std::to_string(list.shards.size() - parts) + " probe shards)";
    }
    return text;
}

} // namespace specula
