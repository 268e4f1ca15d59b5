#pragma once
// `specula-cook bake --slurm`: a level's bake as a Slurm job array (slurm_bake.h).
#include "assetcooker/lib/cli/bake_args.h"

#include <optional>
#include <ostream>
#include <string>

namespace specula::cook {

struct SlurmArgs {
    bool slurm = false;
    std::string partition, time;
    int maxParallel = 0, retries = 2;
    std::optional<int> shardRows; // --shard-rows (light field)
};

// Adds --slurm, --partition, --max-parallel, --time, --retries and --shard-rows to `bake`.
void addSlurmOptions(CLI::App* bake, SlurmArgs& s);

// Writes the shard list and bakes it on the cluster; prints progress and the outcome. Exit
// status 1 (with the report on `out`) when shards failed every attempt or the merge failed.
int runSlurmBake(const BakeArgs& a, const SlurmArgs& s, std::ostream& out);

} // namespace specula::cook
