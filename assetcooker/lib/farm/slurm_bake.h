#pragma once
// A level's or a PEM's shards (shard_bake.h) baked on a Slurm cluster: a job array of
// `specula-cook bake-shard DIR --shard I` over the leaf shards the store lacks (a distance
// probe, a light-field part, a PEM trace: the shards with no dependencies), a second array
// over the dependent shards it lacks (a light-field probe assembling its parts, a PEM sample
// inferring its maps) once the first succeeded (--dependency=afterok), then a job running
// `specula-cook merge DIR` once that succeeded, which installs the level (or the PEM). The
// files, beside the store:
//
//   DIR/.shards/slurm/shard.sh, dependent.sh, merge.sh     the batch scripts
//   DIR/.shards/slurm/logs/shard-I-jobJ.log  task I of array job J (stdout and stderr)
//   DIR/.shards/slurm/logs/merge-jobJ.log    the merge job
//
// The scheduler is asked through a ProcessRunner (sbatch --parsable, squeue, scancel), so
// tests can stand in for it. DIR, SCENE and the specula-cook executable must be visible at
// the same paths on every node (a shared folder); the jobs run in the submitter's working
// directory. A shard is done when its output is in the store (renamed in whole by bake-shard),
// so a killed task never leaves half a shard for the merge to take.
#include "assetcooker/lib/os/process_runner.h"

#include <ostream>
#include <string>
#include <vector>

namespace specula {

struct SlurmOptions {
    std::string cook;      // the specula-cook the jobs run (default: this executable)
    std::string partition; // empty: the cluster's default partition
    std::string time;      // --time of each job (Slurm's format); empty: the partition's
    int maxParallel = 0;   // at most this many shards at once (the array's %N); 0: no limit
    int retries = 2;       // a failed shard is resubmitted this many times
    double pollSeconds = 1;
    bool progress = true; // a progress bar on the terminal
    // The submitter's output lock holder (OutputLock::holder): the batch scripts export it as
    // SPECULA_COOK_LOCK_HOLDER, so the jobs run under its lock. Empty: the jobs lock for
    // themselves.
    std::string lockHolder;
};

struct SlurmShardFailure {
    int index = 0;
    std::string probe;   // the probe's name
    int part = -1;       // a light-field part's part, a PEM shard's sample (-1: a whole probe)
    std::string label;   // shardLabel's: "probe NAME[, part P: slab S rows J0 .. J1]", ...
    std::string state;   // the task's last state (FAILED, CANCELLED, TIMEOUT, ...)
    std::string log;     // its log file
    std::string logTail; // the log's last lines
};

struct SlurmBakeResult {
    std::vector<std::vector<int>> arrays;          // the leaf shards of each first array submitted
    std::vector<std::vector<int>> dependentArrays; // the shards of each second array
    std::vector<std::string> jobs;                 // every job id submitted, in order
    std::vector<SlurmShardFailure> failures; // shards that failed every attempt (nothing merged)
    std::string mergeState;                  // the merge job's end state ("" when not run)
    std::string mergeLog;
    bool merged = false;
    double shardWallSeconds = 0;    // first submission to the last shard's end
    double shardComputeSeconds = 0; // the shards' own bake times (from their logs)
    int shardsBaked = 0;            // leaf shards computed by the jobs
    double seconds = 0;
};

// Submits the leaf shards DIR's store lacks (leafShardsToBake) (readShardList:
// DIR/.shards/shards.json must exist), the dependent ones (dependentShardsToBake) and the
// merge, follows them to the end and resubmits failed shards up to options.retries times (a
// failed leaf cancels that submission's second array and merge; a failed dependent is
// resubmitted in a second array of its own). Never throws for a failed job: failures and the
// merge's state are in the result. Throws Error naming the command when the scheduler refuses a
// submission. A cancel request (cancelRequested: SIGINT/SIGTERM under a SignalGuard) cancels
// every job submitted (scancel, the merge job with them), waits for them to end and throws
// Cancelled naming them: nothing is merged.
SlurmBakeResult bakeOnSlurm(const std::string& dir, const SlurmOptions& options,
                            ProcessRunner& runner, std::ostream* log);

// The report of a bake that did not merge: each failed shard by index, probe (and part), state, log
// and the log's last lines; or the merge job's state and log.
std::string slurmFailureReport(const SlurmBakeResult& r);

} // namespace specula
