#include "assetcooker/lib/cli/shard_commands.h"

#include "assetcooker/lib/cli/bake_args.h"
#include "assetcooker/lib/cli/signal_guard.h"
#include "assetcooker/lib/farm/farm_sim.h"
#include "assetcooker/lib/farm/shard_bake.h"
#include "assetcooker/lib/os/output_lock.h"
#include "engine/core/error.h"
#include "engine/image_io/image_io.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include <memory>

namespace specula::cook {

namespace {

constexpr const char* kShardsDescription =
    "Writes the shard list of a level's bake: what `specula-cook bake SCENE --out DIR` would\n"
    "bake, split into independent, deterministic shards, each keyed by a content hash of its\n"
    "inputs (the geometry in the probe's reach, the sky, the options and the probe's\n"
    "volumes). A distance level: one shard per probe. A light-field level: each probe's rays\n"
    "are split into 6 x ceil(NUM / --shard-rows) part shards (one slab's block of camera\n"
    "rows each), then the probe's own shard, which assembles its parts. The list goes to\n"
    "DIR/.shards/shards.json; prints \"N shards\". Then `specula-cook bake-shard DIR --shard\n"
    "I` for I = 0 .. N-1 (any order, on any machine that sees DIR and SCENE; a probe shard\n"
    "after its parts, or leave it to merge) and `specula-cook merge DIR`: the merged level\n"
    "is byte-identical to a plain bake with the same options, whatever --shard-rows. Takes\n"
    "every option of `bake`.\n"
    "\n"
    "A PEM (--flavour pem, one probe): a trace shard per parameter sample (its reflector\n"
    "rays, DIR/.shards/<hash>.trace), then a sample shard per sample that reads its own\n"
    "trace and the head of every other (self hits and off-hull points; none with\n"
    "--local-layer off), decides the local layer as the plain bake does and infers that\n"
    "sample's maps (DIR/.shards/<hash>.map). merge writes the PEM folder\n"
    "DIR/pem/, byte-identical to `specula-cook bake SCENE --flavour pem --out DIR/pem` with\n"
    "the same options (DIR itself holds the store, which a probe folder may not).\n";

constexpr const char* kBakeShardDescription =
    "Computes shard I of DIR's shard list (written by `specula-cook shards`) into the shard\n"
    "store (a probe's folder DIR/.shards/<hash>/, a light-field part's DIR/.shards/<hash>.rows):\n"
    "written beside it, then renamed, so a killed run leaves no half shard; a shard already in\n"
    "the store (same hash) is skipped. A light-field probe shard traces nothing: it assembles\n"
    "its part shards, which must be in the store (the missing ones are named); a PEM sample\n"
    "shard reads the trace shards likewise. A scene edited since the list was written is\n"
    "refused (run `specula-cook shards` again).\n";

constexpr const char* kMergeDescription =
    "Assembles the level from DIR's shard store: first the light-field probe shards (or PEM\n"
    "sample shards) not yet baked, from their dependencies; then every probe's folder\n"
    "DIR/<probe>/ (each replaced atomically) and the level index DIR/level.json, or a PEM's\n"
    "folder DIR/pem/: the same bytes a plain `specula-cook bake` writes. Refuses, naming them and "
    "writing nothing, when\n"
    "shards are missing or a part is malformed. Every shard it reads is checked against its\n"
    "checksums (DIR/.shards/<hash>.sum.json, written by bake-shard): one tampered with,\n"
    "truncated or swapped is refused, naming the shard and the file. The store is kept (a\n"
    "re-run of bake-shard skips what it holds). One writer at a time: merge holds DIR.lock,\n"
    "bake-shard holds it shared.\n";

constexpr const char* kFarmDescription =
    "Predicts a sharded bake's wall time on a farm of N identical nodes, from the seconds\n"
    "recorded for each shard (DIR/.shards/<hash>.time.json, by bake-shard or by the merge that\n"
    "computed it) and the merge's own (DIR/.shards/merge.time.json less the dependent shards\n"
    "it computed; 0 when not recorded). The model is the Slurm bake's: the leaf shards (a\n"
    "distance probe, a light-field part, a PEM trace) as one job array, longest first, each\n"
    "onto the node free first (list scheduling), each paying the scheduling overhead S on its\n"
    "node; once every leaf is done the dependent shards (a light-field probe, a PEM sample's\n"
    "maps) as a second array the same way; then the merge job (S + the merge's seconds). The\n"
    "ideal is all shards' total / N. Prints nodes, predicted wall, ideal and their ratio for\n"
    "each DIR; writes them as CSV (--csv) and as a plot (--plot). Every shard needs a recorded\n"
    "time: the missing ones are named.\n";

constexpr const char* kFooter =
    "exit status: 0 ok, 1 the input could not be processed, 2 bad command line\n";
// bake-shard and merge run under a SignalGuard: a signal (Ctrl-C, scancel) cancels.
constexpr const char* kCancellableFooter =
    "exit status: 0 ok, 1 the input could not be processed, 2 bad command line, 130\n"
    "cancelled by SIGINT/SIGTERM (scancel): nothing half-written is left in the store or DIR\n";

int runShards(const BakeArgs& a, std::ostream& out) {
    const CookOptions options = checkedCookOptions(a);
    const OutputLock lock(options.out, "shards", FileLockMode::Exclusive);
    ProbeScene scene(options.scene, options.sky);
    const LevelCookOptions sharded = shardedCookOptions(a, options, scene, "SCENE");
    const int rows = checkedShardRows(a, options);
    const ShardList list = writeShardList(scene, sharded, &out, rows);
    out << describeShards(list) << " -> " << shardListPath(a.out) << "\n";
    return cli::kExitOk;
}

struct FarmArgs {
    std::vector<std::string> dirs;
    std::vector<int> nodes{1, 4, 16, 64};
    double overhead = 0.8;
    std::string csv, plot;
};

int runFarm(FarmArgs a, std::ostream& out) {
    std::sort(a.nodes.begin(), a.nodes.end());
    a.nodes.erase(std::unique(a.nodes.begin(), a.nodes.end()), a.nodes.end());
    std::vector<FarmLevel> levels;
    for (const std::string& dir : a.dirs) {
        FarmLevel l;
        l.label = std::filesystem::path(dir).lexically_normal().filename().string();
        if (l.label.empty()) l.label = std::filesystem::path(dir).parent_path().filename().string();
        l.times = readFarmTimes(dir);
        l.rows = simulateFarm(l.times, a.nodes, a.overhead);
        levels.push_back(std::move(l));
    }
    char line[200];
    for (const FarmLevel& l : levels) {
        std::snprintf(
            line, sizeof line,
            "%s: %zu shards + %zu dependent shards, %.3f s in all (longest leaf %.3f "
            "s), merge %.3f s%s, overhead %.3g s a shard\n",
            l.label.c_str(), l.times.shards.size(), l.times.dependents.size(), l.times.total(),
            l.times.shards.empty()
                ? 0.0
                : std::max_element(l.times.shards.begin(), l.times.shards.end(),
                                   [](auto& x, auto& y) { return x.seconds < y.seconds; })
                      ->seconds,
            l.times.mergeSeconds, l.times.mergeRecorded ? "" : " (not recorded)", a.overhead);
        out << line;
        out << "  nodes   wall s  ideal s  wall/ideal\n";
        for (const FarmRow& r : l.rows) {
            std::snprintf(line, sizeof line, "  %5d %8.3f %8.3f %10.2f\n", r.nodes, r.wall, r.ideal,
                          r.ratio);
            out << line;
        }
    }
    const std::string csv =
        a.csv.empty() ? (std::filesystem::path(a.dirs.front()) / "farm.csv").string() : a.csv;
    writeFarmCsv(csv, levels);
    out << "table -> " << csv << "\n";
    if (!a.plot.empty()) {
        writeImage(a.plot, farmPlot(levels, a.overhead));
        out << "plot -> " << a.plot << "\n";
    }
    return cli::kExitOk;
}

} // namespace

void addShardCommands(cli::ToolCli& tool) {
    auto a = std::make_shared<BakeArgs>();
    CLI::App* shards = tool.addSubcommand(
        "shards", "write a level's or a PEM's shard list (for bake-shard and merge)",
        kShardsDescription, kFooter, [a](std::ostream& out) { return runShards(*a, out); });
    addBakeOptions(tool, shards, *a);
    addShardRowsOption(shards, a->shardRows);

    struct ShardArgs {
        std::string dir;
        int shard = -1;
    };
    auto s = std::make_shared<ShardArgs>();
    CLI::App* bake =
        tool.addSubcommand("bake-shard", "compute one shard of a level bake into its shard store",
                           kBakeShardDescription, kCancellableFooter, [s](std::ostream& out) {
                               const SignalGuard guard; // scancel: no half-written shard
                               // Shards of one level may bake at once; a bake or merge not.
                               const OutputLock lock(s->dir, "bake-shard", FileLockMode::Shared);
                               const ShardOutcome r = bakeShard(s->dir, s->shard, &out);
                               if (r.skipped)
                                   out << "shard " << s->shard
                                       << ": already in the store, skipped -> " << r.folder << "\n";
                               else
                                   out << "shard " << s->shard << ": baked in " << r.seconds
                                       << " s -> " << r.folder << "\n";
                               return cli::kExitOk;
                           });
    bake->add_option("DIR", s->dir, "the level folder holding .shards/shards.json")->required();
    bake->add_option("--shard", s->shard, "the shard's index in the list (0 .. N-1)")->required();

    auto dir = std::make_shared<std::string>();
    CLI::App* merge = tool.addSubcommand(
        "merge", "assemble a level's cooked probes and index from its shard store",
        kMergeDescription, kCancellableFooter, [dir](std::ostream& out) {
            const SignalGuard guard;
            const OutputLock lock(*dir, "merge", FileLockMode::Exclusive);
            const LevelCookResult r = mergeShards(*dir, &out);
            out << "merged " << r.probes.size() << (r.probes.size() == 1 ? " probe" : " probes")
                << " in " << r.seconds << " s -> " << r.index << "\n";
            return cli::kExitOk;
        });
    merge->add_option("DIR", *dir, "the level folder holding .shards/")->required();

    auto f = std::make_shared<FarmArgs>();
    CLI::App* farm = tool.addSubcommand(
        "farm", "predict a sharded bake's wall time on 1 .. N farm nodes from its shard times",
        kFarmDescription, kFooter, [f](std::ostream& out) { return runFarm(*f, out); });
    farm->add_option("DIR", f->dirs,
                     "level folders whose shards were baked with bake-shard (one line each)")
        ->required();
    farm->add_option("--nodes", f->nodes, "node counts to simulate (default 1,4,16,64)")
        ->delimiter(',')
        ->check(CLI::Range(1, 1000000));
    farm->add_option("--overhead", f->overhead,
                     "scheduling overhead a shard, seconds (default 0.8: the one-node Slurm "
                     "cluster of scripts/local-slurm, CHANGELOG.md)")
        ->check(CLI::Range(0.0, 1e6));
    farm->add_option("--csv", f->csv, "the table as CSV (default: the first DIR's farm.csv)");
    farm->add_option("--plot", f->plot, "wall time against nodes as an image (e.g. farm.png)");
}

} // namespace specula::cook
