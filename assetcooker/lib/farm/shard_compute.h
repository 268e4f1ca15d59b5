#pragma once
// What bake-shard and merge share (shard_bake.cpp, shard_merge.cpp): computing one shard
// from the store and recording how long it took.
#include "assetcooker/lib/farm/shard_bake.h"

#include <ostream>
#include <string>

namespace specula {

// Computes shard `index` (not in the store) on `scene`: a part's block, or a probe's folder
// (a light-field probe's assembled from its parts), or a PEM shard.
void computeShard(const std::string& dir, const ShardList& list, int index, ProbeScene& scene,
                  std::ostream* log);

// "shard I (label)": what a shard's time file says it timed.
std::string timeWhat(const ShardList& list, int index);

// {"format": "specula-shard-time", "version": 1, "what": ..., "seconds": ..., "by": ...},
// atomically; by: "bake-shard" or "merge" (a dependent shard computed by mergeShards, whose
// time is in merge.time.json's too). merge.time.json adds "assembly_seconds": the part of its
// seconds spent computing dependents (farm_sim.h counts them as the second array's).
void writeTime(const std::string& file, const std::string& what, double seconds,
               const std::string& by = "bake-shard", double assemblySeconds = -1);

} // namespace specula
