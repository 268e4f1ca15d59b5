#pragma once
// A simulated render farm for a sharded level bake (shard_bake.h): what the bake's wall time
// would be on N identical nodes, from the shard times bake-shard recorded in the store
// (DIR/.shards/<hash>.time.json) and a scheduler's overhead per shard. The shards simulated
// are the two job arrays a Slurm bake submits (slurm_bake.h): the leaves (distance probes,
// light-field parts, PEM traces), then, once every leaf is done, the dependents (light-field
// probes assembling their parts, PEM samples inferring their maps). A dependent's time is
// the one recorded for it, by bake-shard or by the merge that computed it; the merge job's
// own time is merge.time.json's less what it spent computing dependents.
//
// The model: each array by list scheduling, longest shard first (LPT), each shard onto the
// node that is free first; every shard costs the scheduling overhead plus its recorded
// seconds on its node; the dependents' array starts when the leaves' ends (afterok on the
// whole array), and the merge runs after both, as one more job (overhead + its seconds). The
// ideal is all shards' total seconds / N: no overhead, no barrier, no merge, perfect split.
#include "engine/image/image.h"

#include <string>
#include <vector>

namespace specula {

struct FarmShardTime {
    int index = 0;     // in the shard list
    std::string label; // shardLabel: "probe NAME", ", part P: ..." or "PEM sample K: ..."
    double seconds = 0;
};

struct FarmTimes {
    std::string dir;
    std::vector<FarmShardTime> shards;     // the leaves: the first array
    std::vector<FarmShardTime> dependents; // the second array, after every leaf
    double mergeSeconds = 0;               // the merge job's own (without computing dependents)
    bool mergeRecorded = false;            // DIR/.shards/merge.time.json was there (else 0 s)
    double total() const;                  // sum of every shard's seconds, leaves and dependents
};

// DIR's shard list and the recorded times. Throws Error naming the list and every shard with
// no time (index, label, expected file), or the time file and field that is malformed.
FarmTimes readFarmTimes(const std::string& dir);

// One job array's wall time on `nodes` nodes (>= 1): LPT list scheduling, `overhead` paid
// before each shard on its node; 0 for no shards. `seconds` in any order.
double arrayWall(std::vector<double> seconds, int nodes, double overhead);

// The predicted wall time of the model above: the leaves' array, then the dependents' array,
// then the merge job (overhead + mergeSeconds).
double farmWall(std::vector<double> leaves, int nodes, double overhead, double mergeSeconds,
                std::vector<double> dependents = {});

struct FarmRow {
    int nodes = 1;
    double wall = 0;  // predicted (farmWall)
    double ideal = 0; // total / nodes
    double ratio = 0; // wall / ideal
};

std::vector<FarmRow> simulateFarm(const FarmTimes& times, const std::vector<int>& nodes,
                                  double overhead);

// The table as CSV: level,shards,dependents,total_s,merge_s,nodes,wall_s,ideal_s,ratio (one
// row per level and node count). Throws Error naming the file when it cannot be written.
struct FarmLevel {
    std::string label; // the level's name in the table and the plot
    FarmTimes times;
    std::vector<FarmRow> rows;
};
void writeFarmCsv(const std::string& file, const std::vector<FarmLevel>& levels);

// Wall time against nodes, both on log2 axes: each level's prediction (solid) and its ideal
// (dashed) in its own colour.
Image farmPlot(const std::vector<FarmLevel>& levels, double overhead, int width = 800,
               int height = 560);

} // namespace specula
