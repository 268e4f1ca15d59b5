#pragma once
// A PEM bake (cookPemAsset, pem_bake.h) as shards (shard_bake.h). The local layer's decision
// and sphere are the asset's, made from every sample's trace, so the samples split in two
// kinds:
//
//   "pem-trace", part k   a leaf: sample k's reflector rays (PemBake::trace), written to
//                         DIR/.shards/<hash>.trace (pem_shard_files.h)
//   "pem-sample", part k  depends on every trace shard (only on trace k under
//                         --local-layer off, where nothing is decided from the others): the
//                         decision (decidePemLocalLayer) from all the traces, then sample
//                         k's maps (PemBake::infer), written to DIR/.shards/<hash>.map
//
// A sample shard reads its own trace whole and only the first part of the others: the
// decision's inputs (pemDecisionInputs: whether some off-hull ray meets its own reflector
// again, and the off-hull points), which each trace shard writes ahead of its samples. The
// points themselves are needed: the bounding sphere's radius is the farthest off-hull point
// from a centre known only once all are in, and the fitted sphere is a least squares over all
// of them in the one-machine bake's order, so no fixed-size summary gives the same bits. The
// merge (mergeShards) writes the PEM folder DIR/pem/ from the sample shards, byte for byte
// the folder `specula-cook bake` writes; DIR itself holds the store, which a probe folder may
// not.
//
// The list's level index holds the PEM as one probe entry (name and folder "pem", at the
// bake's centre, its proxy the whole scene's bounds) whose inputs are levelProbeInputs': the
// hashes and the scene-unchanged check (shard_install.h) work as for a level's probe.
#include "assetcooker/lib/farm/shard_bake.h"

#include <ostream>
#include <string>
#include <vector>

namespace specula {

inline constexpr const char* kPemTraceShard = "pem-trace";   // one sample's rays
inline constexpr const char* kPemSampleShard = "pem-sample"; // one sample's maps
inline constexpr const char* kPemFolder = "pem";             // DIR/pem/: the merged asset

bool isPemList(const ShardList& list);
// The PEM's samples (the settings').
int pemListSamples(const ShardList& list);

// The level index and the shards (hashes unset) of a PEM bake of `scene` with `options`
// (options.flavour a PemCookSettings; the centre options.probeCentre, else the markup's).
// Validates the settings: Error naming the scene and the field.
void planPemShards(ProbeScene& scene, const CookOptions& options, ShardList& list);

// The shards pem-sample shard `index` reads (see above); empty for a trace shard.
std::vector<int> pemShardDependencies(const ShardList& list, int index);

// Computes PEM shard `index` of DIR's list on `scene` into the store (atomically); a sample
// shard reads its traces, which bakeShard and mergeShards have checked are present (Error
// naming a malformed one).
void computePemShard(const std::string& dir, const ShardList& list, int index, ProbeScene& scene);

// Writes DIR/pem/ from the sample shards (all present: mergeShards checks) on `scene`. A
// sample whose view held no reflector pixel is left out: a warning each, returned. Error
// when every sample was left out.
std::vector<std::string> installPemShards(const std::string& dir, const ShardList& list,
                                          ProbeScene& scene);

} // namespace specula
