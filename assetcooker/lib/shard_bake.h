#pragma once
// A level's bake as a list of independent, deterministic shards (DESIGN §9), for bakes that
// outgrow one machine. Phase 1: one shard per probe (kind "probe", part 0), keyed by a
// content hash of everything its bytes depend on: the probe's input checksums (the geometry
// in its reach, the sky, the options text and its volumes: levelProbeInputs) and the
// flavour's full settings. The files:
//
//   DIR/.shards/shards.json   the list (writeShardList): the scene, the sky, the settings,
//                             the planned level index and each shard's kind, probe, part, hash
//   DIR/.shards/<hash>/       one computed shard: the probe's cooked folder, exactly as a
//                             plain bake writes it (bakeShard: written beside, then renamed)
//   DIR/.shards/<hash>.time.json  the seconds bakeShard took for it (load + bake), for the farm
//                             simulation (farm_sim.h); beside the folder, so merge never
//                             installs it and the merged bytes do not depend on it
//   DIR/.shards/merge.time.json   the seconds the last mergeShards took
//
// mergeShards installs every shard's folder as DIR/<probe folder>/ and writes DIR/level.json:
// the same files, byte for byte, as cookLevel (level_bake.h), which runs the same shards
// in-process, whatever the shard count and order. A later phase runs bakeShard as a Slurm
// job array.
#include "assetcooker/lib/level_bake.h"

#include <nlohmann/json.hpp>

#include <ostream>
#include <string>
#include <vector>

namespace specula {

struct Shard {
    std::string kind = "probe"; // what the shard computes; phase 1: a whole probe
    int probe = 0;              // index into the level's probes
    int part = 0;               // the part of the probe (0 for a whole probe)
    std::string hash;           // content hash of its inputs: its folder in the store
};

struct ShardList {
    std::string scene, sky;
    nlohmann::json settings; // the flavour's settings (cookSettingsToJson)
    LevelIndex level;        // the planned index (no manifest checksums yet)
    std::vector<Shard> shards;
};

// The flavour's settings as JSON and back (for the shard list and the shard hash).
nlohmann::json cookSettingsToJson(const CookFlavour& flavour);
CookFlavour cookSettingsFromJson(const nlohmann::json& j, const std::string& file);

// DIR/.shards: the store; DIR/.shards/shards.json: the list.
std::string shardStore(const std::string& dir);
std::string shardListPath(const std::string& dir);

// DIR/.shards/<hash>.time.json and DIR/.shards/merge.time.json (see above).
std::string shardTimePath(const std::string& dir, const Shard& s);
std::string mergeTimePath(const std::string& dir);

// Plans the level (options.cook.out is DIR) and writes the shard list atomically; returns it.
// Throws Error naming the file and field.
ShardList writeShardList(ProbeScene& scene, const LevelCookOptions& options, std::ostream* log);
// DIR's shard list; throws Error naming it when it is missing or no shard list.
ShardList readShardList(const std::string& dir);

struct ShardOutcome {
    bool skipped = false; // the store already held a shard with this hash
    std::string folder;   // DIR/.shards/<hash>
    double seconds = 0;
};

// Computes shard `index` of DIR's list into the store (atomic: written beside, then renamed);
// a shard already there (same hash) is skipped. Throws Error naming the list and the count
// when the index is out of range.
ShardOutcome bakeShard(const std::string& dir, int index, std::ostream* log);

// Installs every shard's probe folder in DIR and writes DIR/level.json (the level's as cookLevel
// writes it). Throws Error naming the missing shards (index, probe, hash) and writes nothing
// when any is missing.
LevelCookResult mergeShards(const std::string& dir, std::ostream* log);

} // namespace specula
