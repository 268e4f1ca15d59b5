#include "shard_commands.h"

#include "assetcooker/lib/bake_args.h"
#include "assetcooker/lib/shard_bake.h"
#include "engine/core/error.h"

#include <memory>

namespace specula::cook {

namespace {

constexpr const char* kShardsDescription =
    "Writes the shard list of a level's bake: what `specula-cook bake SCENE --out DIR` would\n"
    "bake, split into independent, deterministic shards (one per probe), each keyed by a\n"
    "content hash of its inputs (the geometry in the probe's reach, the sky, the options and\n"
    "the probe's volumes). The list goes to DIR/.shards/shards.json; prints \"N shards\".\n"
    "Then `specula-cook bake-shard DIR --shard I` for I = 0 .. N-1 (any order, on any\n"
    "machine that sees DIR and SCENE) and `specula-cook merge DIR`: the merged level is\n"
    "byte-identical to a plain bake with the same options. Takes every option of `bake`.\n";

constexpr const char* kBakeShardDescription =
    "Computes shard I of DIR's shard list (written by `specula-cook shards`) into the shard\n"
    "store DIR/.shards/<hash>/: written beside it, then renamed, so a killed run leaves no\n"
    "half shard; a shard already in the store (same hash) is skipped.\n";

constexpr const char* kMergeDescription =
    "Assembles the level from DIR's shard store: every probe's folder DIR/<probe>/ (each\n"
    "replaced atomically) and the level index DIR/level.json, the same bytes a plain\n"
    "`specula-cook bake` writes. Refuses, naming them and writing nothing, when shards are\n"
    "missing. The store is kept (a re-run of bake-shard skips what it holds).\n";

constexpr const char* kFooter =
    "exit status: 0 ok, 1 the input could not be processed, 2 bad command line\n";

int runShards(const BakeArgs& a, std::ostream& out) {
    const CookOptions options = checkedCookOptions(a);
    ProbeScene scene(options.scene, options.sky);
    if (!isLevel(a, scene))
        throw UsageError("SCENE", a.scene + " has one probe: `specula-cook bake` bakes it (shards "
                                            "split a level: several probes, --probe twice or "
                                            "--probes FILE)");
    const ShardList list = writeShardList(scene, levelCookOptions(a, options, scene), &out);
    out << list.shards.size() << " shards -> " << shardListPath(a.out) << "\n";
    return cli::kExitOk;
}

} // namespace

void addShardCommands(cli::ToolCli& tool) {
    auto a = std::make_shared<BakeArgs>();
    CLI::App* shards = tool.addSubcommand(
        "shards", "write a level bake's shard list (for bake-shard and merge)", kShardsDescription,
        kFooter, [a](std::ostream& out) { return runShards(*a, out); });
    addBakeOptions(tool, shards, *a);

    struct ShardArgs {
        std::string dir;
        int shard = -1;
    };
    auto s = std::make_shared<ShardArgs>();
    CLI::App* bake =
        tool.addSubcommand("bake-shard", "compute one shard of a level bake into its shard store",
                           kBakeShardDescription, kFooter, [s](std::ostream& out) {
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
        kMergeDescription, kFooter, [dir](std::ostream& out) {
            const LevelCookResult r = mergeShards(*dir, &out);
            out << "merged " << r.probes.size() << " probes in " << r.seconds << " s -> " << r.index
                << "\n";
            return cli::kExitOk;
        });
    merge->add_option("DIR", *dir, "the level folder holding .shards/")->required();
}

} // namespace specula::cook
