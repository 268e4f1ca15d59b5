#include "assetcooker/lib/cli/slurm_command.h"

#include "assetcooker/lib/cli/signal_guard.h"
#include "assetcooker/lib/farm/shard_bake.h"
#include "assetcooker/lib/farm/slurm_bake.h"
#include "assetcooker/lib/flavours/pem/shard_pem.h"
#include "assetcooker/lib/os/output_lock.h"
#include "components/reflection_probe/writer/probe_folder.h"
#include "engine/core/error.h"

#include <filesystem>

namespace specula::cook {

void addSlurmOptions(CLI::App* bake, SlurmArgs& s) {
    CLI::Option* slurm = bake->add_flag(
        "--slurm", s.slurm,
        "bake a level's probes, or a PEM's samples, as Slurm job arrays (sbatch, squeue and\n"
        "scancel in PATH): one task a leaf shard (see `specula-cook shards`: a distance probe,\n"
        "a light-field part, a PEM sample's trace), then a second array of the dependent shards\n"
        "(a light-field probe assembling its parts, a PEM sample's maps) once all succeeded,\n"
        "then a merge job once those did (a PEM goes to DIR/pem/). DIR,\n"
        "SCENE, the sky and this specula-cook must be visible at the same paths on every node\n"
        "(a shared folder); jobs run in the current directory. Re-running resumes: shards\n"
        "already in DIR/.shards are not resubmitted. Batch scripts and logs go to\n"
        "DIR/.shards/slurm/");
    bake->add_option("--partition", s.partition,
                     "with --slurm: the partition (default: the "
                     "cluster's default)")
        ->needs(slurm)
        ->check(cli::nonEmpty("a partition name"));
    bake->add_option("--max-parallel", s.maxParallel,
                     "with --slurm: at most N shards run at once (the array's %N; 0: no limit)")
        ->needs(slurm)
        ->check(CLI::Range(0, 1000000));
    bake->add_option("--time", s.time,
                     "with --slurm: each job's time limit, in Slurm's format (e.g. 30, 1:00:00)")
        ->needs(slurm)
        ->check(cli::nonEmpty("a time limit"));
    bake->add_option("--retries", s.retries,
                     "with --slurm: a failed, cancelled or timed-out shard is resubmitted up to N "
                     "times, then reported by index and reason (nothing is merged)")
        ->needs(slurm)
        ->check(CLI::Range(0, 100))
        ->capture_default_str();
    addShardRowsOption(bake, s.shardRows)->needs(slurm);
}

int runSlurmBake(const BakeArgs& args, const SlurmArgs& s, std::ostream& out) {
    BakeArgs a = args;
    a.shardRows = s.shardRows;
    const CookOptions options = checkedCookOptions(a);
    const int rows = checkedShardRows(a, options);
    // A signal cancels the jobs submitted so far (bakeOnSlurm), never leaving them to merge.
    const SignalGuard guard;
    const OutputLock lock(options.out, "bake --slurm", FileLockMode::Exclusive);
    ProbeScene scene(options.scene, options.sky);
    throwIfCancelled(options.out);
    const ShardList list =
        writeShardList(scene, shardedCookOptions(a, options, scene, "--slurm"), &out, rows);
    out << describeShards(list) << " -> " << shardListPath(a.out) << "\n";
    SlurmOptions o;
    o.partition = s.partition;
    o.time = s.time;
    o.maxParallel = s.maxParallel;
    o.retries = s.retries;
    o.lockHolder = lock.holder();
    SystemProcessRunner runner;
    const SlurmBakeResult r = bakeOnSlurm(a.out, o, runner, &out);
    if (!r.merged) {
        out << slurmFailureReport(r);
        throw Error(shardListPath(a.out), "shards",
                    r.failures.empty() ? "the merge job failed (see above)"
                                       : std::to_string(r.failures.size()) +
                                             " shards failed every attempt; nothing was merged "
                                             "(see above)");
    }
    const bool pem = isPemList(list);
    out << (pem ? "pem: " : "level: ") << list.shards.size() << " shards, " << r.shardsBaked
        << " baked on slurm in " << r.arrays.size() + r.dependentArrays.size()
        << " array submissions (" << r.shardWallSeconds << " s, shards' own bake "
        << r.shardComputeSeconds << " s), merged, total " << r.seconds << " s -> "
        << (pem ? std::filesystem::path(a.out) / kPemFolder / "manifest.json"
                : std::filesystem::path(a.out) / "level.json")
               .string()
        << "\n";
    return cli::kExitOk;
}

} // namespace specula::cook
