#pragma once
// A level's bake as a list of independent, deterministic shards (docs/design.md §9), for bakes that
// outgrow one machine. Each shard is keyed by a content hash of everything its bytes depend
// on: the probe's input checksums (the geometry in its reach, the sky, the options text and
// its volumes: levelProbeInputs), the flavour's full settings, the shard's kind and part.
//
// A distance level: one shard per probe (kind "probe", part 0); its bake is a GPU raster of
// six faces, fast enough whole. A light-field level: each probe is split further, as its
// rays dominate the bake (6 slabs x NUM^2 cameras x RES^2): part shards of kind
// "lightfield-rows", part = slab * blocksPerSlab + block, each tracing one slab's camera rows
// [block * rows, min(NUM, (block + 1) * rows)) (rows: the list's shard_rows, default NUM, one
// part per slab; it is in each part's hash, not the probe's: the probe's bytes do not depend
// on it), listed before their probe's "probe" shard, which traces nothing: it assembles its
// parts (lightfield_rows.h) and writes the probe's folder exactly as a plain bake does. A
// shard with no dependencies (a part, a distance probe) is a leaf: what a farm runs.
//
// A PEM bake (shard_pem.h): a "pem-trace" leaf per parameter sample, then a "pem-sample"
// shard per sample depending on the traces (the local layer is decided from all of them);
// the merge writes the PEM folder DIR/pem/. The probe shards and the PEM sample shards are
// the final shards: the level (or the PEM) is made of them.
//
//   DIR/.shards/shards.json   the list (writeShardList): the scene, the sky, the settings,
//                             shard_rows, the planned level index and each shard's kind,
//                             probe, part, hash
//   DIR/.shards/<hash>/       one computed probe shard: the probe's cooked folder, exactly as
//                             a plain bake writes it (bakeShard: written beside, then renamed)
//   DIR/.shards/<hash>.rows   one computed part shard (writeLightFieldRows, atomically)
//   DIR/.shards/<hash>.trace, <hash>.map   one PEM trace, one PEM sample's maps
//                             (pem_shard_files.h, atomically)
//   DIR/.shards/<hash>.time.json  the seconds bakeShard took for it (load + bake), for the farm
//                             simulation (farm_sim.h); beside the folder, so merge never
//                             installs it and the merged bytes do not depend on it
//   DIR/.shards/merge.time.json   the seconds the last mergeShards took (with the assembly
//                             of the probe shards it baked)
//
// mergeShards assembles the probe shards whose parts are all present, then installs every
// probe shard's folder as DIR/<probe folder>/ and writes DIR/level.json: the same files, byte
// for byte, as cookLevel (level_bake.h), which bakes each probe whole in-process, whatever
// the shard count, the rows a part and the order. slurm_bake.h runs the leaves as a Slurm job
// array, the final shards with dependencies as a second array after it, and the merge as a
// job after that.
#include "assetcooker/lib/bake/cook_settings_json.h"
#include "assetcooker/lib/level/level_bake.h"

#include <nlohmann/json.hpp>

#include <ostream>
#include <string>
#include <vector>

namespace specula {

inline constexpr const char* kProbeShard = "probe";                    // a whole probe's folder
inline constexpr const char* kLightFieldRowsShard = "lightfield-rows"; // a block of a probe

struct Shard {
    std::string kind = kProbeShard; // what the shard computes (see above)
    int probe = 0;                  // index into the level's probes
    int part = 0;                   // the part of the probe (0 for a whole probe)
    std::string hash;               // content hash of its inputs: its name in the store
    // A "lightfield-rows" part: the slab and camera rows [j0, j1) it traces (from part and
    // the list's shard_rows; not in the file).
    int slab = 0, j0 = 0, j1 = 0;
};

struct ShardList {
    std::string scene, sky;
    nlohmann::json settings; // the flavour's settings (cookSettingsToJson)
    // Light field: the camera rows a part shard traces (1 .. NUM); 0 for a distance level.
    int shardRows = 0;
    LevelIndex level; // the planned index (no manifest checksums yet)
    std::vector<Shard> shards;
};

// DIR/.shards: the store; DIR/.shards/shards.json: the list.
std::string shardStore(const std::string& dir);
std::string shardListPath(const std::string& dir);

// DIR/.shards/<hash>.time.json and DIR/.shards/merge.time.json (see above).
std::string shardTimePath(const std::string& dir, const Shard& s);
std::string mergeTimePath(const std::string& dir);
// Where a computed shard lies: DIR/.shards/<hash>/ (probe) or DIR/.shards/<hash>.rows (part).
std::string shardOutputPath(const std::string& dir, const Shard& s);
// Whether the store holds the shard (a probe folder's manifest, a part's or PEM shard's file).
bool shardPresent(const std::string& dir, const Shard& s);
// A probe shard or a PEM sample shard: what the merge installs (see above).
bool isFinalShard(const Shard& s);

// The shards `index` depends on (a light-field probe shard: its parts; a PEM sample shard:
// the trace shards), in list order; empty for a leaf.
std::vector<int> shardDependencies(const ShardList& list, int index);
// The leaves a bake still needs, in list order: those not in the store, except the parts of
// probe shards already there.
std::vector<int> leafShardsToBake(const std::string& dir, const ShardList& list);
// The final shards with dependencies the store lacks (light-field probes, PEM samples), in
// list order: what a farm runs once the leaves are in.
std::vector<int> dependentShardsToBake(const std::string& dir, const ShardList& list);
// "probe NAME", "probe NAME, part P: slab S rows J0 .. J1-1", "PEM sample K: trace" or
// "PEM sample K: maps", for reports.
std::string shardLabel(const ShardList& list, int index);

// "N shards", with "(P light-field part shards of R camera rows + Q probe shards)" for a
// light-field level.
std::string describeShards(const ShardList& list);

// Plans the level, or the PEM when options.cook.flavour is a PemCookSettings (one probe:
// options.cook.probeCentre, else the markup's), (options.cook.out is DIR) and writes the
// shard list atomically; returns it.
// shardRows: a light-field level's camera rows a part shard traces, 1 .. NUM (0: NUM, one
// part a slab); ignored for a distance level. Throws Error naming the file and field
// ("shard_rows" when out of range).
ShardList writeShardList(ProbeScene& scene, const LevelCookOptions& options, std::ostream* log,
                         int shardRows = 0);
// DIR's shard list; throws Error naming it when it is missing or no shard list.
ShardList readShardList(const std::string& dir);
// A shard list's JSON (the text of `file`) checked and read: what readShardList does once
// the file is parsed. Throws Error naming `file` and the field.
ShardList shardListFromJson(const nlohmann::json& doc, const std::string& file);

struct ShardOutcome {
    bool skipped = false; // the store already held a shard with this hash
    std::string folder;   // DIR/.shards/<hash>
    double seconds = 0;
};

// Computes shard `index` of DIR's list into the store (atomic: written beside, then renamed);
// a shard already there (same hash) is skipped. A light-field probe shard assembles its parts
// from the store: Error naming the missing part shards by index, or the part file that is
// malformed. Throws Error naming the list and the count when the index is out of range.
ShardOutcome bakeShard(const std::string& dir, int index, std::ostream* log);

// Bakes the final shards missing from the store whose dependencies are all there
// (in-process, in parallel over the probes), then installs every probe shard's folder in DIR
// and writes DIR/level.json (the level's as cookLevel writes it), or a PEM's folder DIR/pem/
// (the folder `specula-cook bake --flavour pem` writes; result.index is its manifest). Throws Error
// naming the missing shards (index, probe, part, hash) and writes nothing in DIR when any leaf the
// level needs is missing or a part is malformed.
LevelCookResult mergeShards(const std::string& dir, std::ostream* log);

} // namespace specula
