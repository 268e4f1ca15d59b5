#pragma once
// A simulated render farm for a sharded level bake (shard_bake.h): what the bake's wall time
// would be on N identical nodes, from the shard times bake-shard recorded in the store
// (DIR/.shards/<hash>.time.json) and a scheduler's overhead per shard. The shards simulated
// are the leaves a job array runs (distance probes, light-field parts); the assembly of the
// light-field probes is the merge job's (in merge.time.json when merge did it, else the probe
// shards' recorded times are added to the merge's).
//
// The model: list scheduling, longest shard first (LPT), each shard onto the node that is
// free first; every shard costs the scheduling overhead plus its recorded seconds on its node;
// the merge runs once all shards are done, as one more job (overhead + the recorded merge
// seconds). The ideal is the shards' total seconds / N: no overhead, no merge, perfect split.
#include "engine/image/image.h"

#include <string>
#include <vector>

namespace specula {

struct FarmShardTime {
    int index = 0;     // in the shard list
    std::string probe; // the probe's name (and "part P" for a light-field part)
    double seconds = 0;
};

struct FarmTimes {
    std::string dir;
    std::vector<FarmShardTime> shards;
    double mergeSeconds = 0;
    bool mergeRecorded = false; // DIR/.shards/merge.time.json was there (else 0 s)
    double total() const;       // sum of the shards' seconds
};

// DIR's shard list and the recorded times. Throws Error naming the list and every leaf shard with
// no time (index, probe, expected file), or the time file and field that is malformed.
FarmTimes readFarmTimes(const std::string& dir);

// The predicted wall time of the model above. `seconds` in any order; nodes >= 1.
double farmWall(std::vector<double> seconds, int nodes, double overhead, double mergeSeconds);

struct FarmRow {
    int nodes = 1;
    double wall = 0;  // predicted (farmWall)
    double ideal = 0; // total / nodes
    double ratio = 0; // wall / ideal
};

std::vector<FarmRow> simulateFarm(const FarmTimes& times, const std::vector<int>& nodes,
                                  double overhead);

// The table as CSV: level,shards,total_s,nodes,wall_s,ideal_s,ratio (one row per level and
// node count). Throws Error naming the file when it cannot be written.
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
