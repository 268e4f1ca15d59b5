#pragma once
// Verify, never trust: every shard in the store carries the checksums of its bytes, written by
// whoever computed it (bake-shard, or the merge for a dependent shard), and the merge checks
// them before it reads or installs anything, so a shard tampered with, truncated, or swapped
// with another's is refused naming the shard and the file.
//
//   DIR/.shards/<hash>.sum.json   {"format": "specula-shard-sum", "version": 1, "shard": hash,
//                                  "kind": kind, "files": {relative path: "fnv1a64:.."}}
//
// A probe shard's files are every file of its folder (relative to it); a part's, a trace's or
// a map's its one file (by name).
#include "assetcooker/lib/farm/shard_bake.h"

#include <string>

namespace specula {

// DIR/.shards/<hash>.sum.json.
std::string shardSumPath(const std::string& dir, const Shard& s);

// Records the checksums of shard s's output in the store (atomically).
void writeShardSum(const std::string& dir, const Shard& s);

// Whether the store holds shard s's checksum file.
bool shardSumPresent(const std::string& dir, const Shard& s);

// Throws Error naming the file and shard `index` (its label and hash) unless its output in the
// store is what its checksum file records: the checksum file missing or naming another shard
// (swapped), a file missing, altered or truncated, or a file it does not record.
void verifyShard(const std::string& dir, const ShardList& list, int index);

} // namespace specula
