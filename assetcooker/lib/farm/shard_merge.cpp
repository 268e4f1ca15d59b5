#include "assetcooker/lib/farm/shard_bake.h"
#include "assetcooker/lib/farm/shard_compute.h"

#include "assetcooker/lib/farm/shard_checksum.h"
#include "assetcooker/lib/farm/shard_install.h"
#include "assetcooker/lib/flavours/pem/shard_pem.h"

#include "components/reflection_probe/manifest_fields.h"
#include "components/reflection_probe/writer/probe_folder.h"
#include "engine/core/error.h"

#include <tbb/parallel_for.h>

#include <chrono>
#include <exception>
#include <filesystem>
#include <optional>
#include <set>
#include <sstream>

// mergeShards (shard_bake.h): the final shards computed from their dependencies, verified,
// and installed as the level (or the PEM).
namespace specula {

namespace fs = std::filesystem;

namespace {

// Every probe shard's folder installed in DIR and DIR/level.json written (cookLevel's bytes).
void installLevel(const std::string& dir, ShardList& list, LevelCookResult& result,
                  std::ostream* log) {
    LevelPlan plan; // the previous index, for the probes no longer in the level
    std::error_code ec;
    if (fs::is_regular_file(fs::path(dir) / "level.json", ec)) try {
            plan.previous = readLevelIndex((fs::path(dir) / "level.json").string());
        } catch (const Error&) {
        }
    for (const Shard& s : list.shards) {
        if (s.kind != kProbeShard) continue;
        LevelProbeEntry& e = list.level.probes[std::size_t(s.probe)];
        const fs::path to = fs::path(dir) / e.folder;
        installShard(shardOutputPath(dir, s), to, list.scene);
        e.manifestChecksum = fileChecksum((to / "manifest.json").string());
        result.probes.push_back({e.volume.name, e.folder, true, "merged", 0.0});
    }
    result.index = (fs::path(dir) / "level.json").string();
    writeLevelIndex(list.level, result.index);
    plan.index = list.level;
    warnOfDroppedProbes(plan, dir, result.warnings, log);
}

} // namespace

LevelCookResult mergeShards(const std::string& dir, std::ostream* log) {
    const auto start = std::chrono::steady_clock::now();
    ShardList list = readShardList(dir);
    // What a killed merge or bake-shard left (DIR/<probe>.tmp-PID, DIR/.shards/<hash>.tmp-PID):
    // under the caller's lock.
    std::ostringstream dropped;
    removeStaleTemporariesIn(dir, log ? *log : dropped);
    removeStaleTemporariesIn(shardStore(dir), log ? *log : dropped);
    const std::vector<int> leaves = leafShardsToBake(dir, list);
    if (!leaves.empty()) {
        std::string missing;
        for (const int i : leaves)
            missing += (missing.empty() ? "" : ", ") + std::to_string(i) + " (" +
                       shardLabel(list, i) + ", " + list.shards[std::size_t(i)].hash + ")";
        throw Error(shardListPath(dir), "shards",
                    std::to_string(leaves.size()) + " of " + std::to_string(list.shards.size()) +
                        " shards not baked: " + missing +
                        "; run specula-cook bake-shard for each (nothing was merged)");
    }
    // The final shards still missing have all their dependencies: computed here (the probe
    // shards in parallel over the probes) before anything is installed (a malformed part
    // stops the merge). A PEM's merge reads the scene in any case: the asset's distance cube.
    std::vector<int> assemble;
    for (std::size_t i = 0; i < list.shards.size(); ++i)
        if (!shardPresent(dir, list.shards[i])) assemble.push_back(int(i));
    // Verify, never trust: every shard the merge reads (the final shards it installs, the
    // dependencies of those it computes) is what was baked, before anything is written.
    std::set<int> read;
    for (std::size_t i = 0; i < list.shards.size(); ++i)
        if (isFinalShard(list.shards[i]) && shardPresent(dir, list.shards[i])) read.insert(int(i));
    for (const int i : assemble)
        for (const int d : shardDependencies(list, i))
            read.insert(d);
    for (const int i : read)
        verifyShard(dir, list, i);
    std::optional<ProbeScene> scene;
    if (!assemble.empty() || isPemList(list)) {
        scene.emplace(list.scene, list.sky);
        const EmbreeScene environment = environmentOf(*scene);
        for (const int i : assemble)
            checkSceneUnchanged(dir, list, i, *scene, environment);
        if (isPemList(list)) checkSceneUnchanged(dir, list, 0, *scene, environment);
    }
    const auto assemblyStart = std::chrono::steady_clock::now();
    if (!assemble.empty()) {
        if (log) *log << "computing " << assemble.size() << " shards from their dependencies\n";
        std::vector<std::exception_ptr> errors(assemble.size());
        auto computeOne = [&](std::size_t k) {
            const auto probeStart = std::chrono::steady_clock::now();
            try {
                computeShard(dir, list, assemble[k], *scene, nullptr);
                writeShardSum(dir, list.shards[std::size_t(assemble[k])]);
                writeTime(
                    shardTimePath(dir, list.shards[std::size_t(assemble[k])]),
                    timeWhat(list, assemble[k]),
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - probeStart)
                        .count(),
                    "merge");
            } catch (...) {
                errors[k] = std::current_exception();
            }
        };
        // A PEM sample's inference runs in parallel itself: one sample at a time.
        if (isPemList(list))
            for (std::size_t k = 0; k < assemble.size(); ++k)
                computeOne(k);
        else
            tbb::parallel_for(std::size_t(0), assemble.size(), computeOne);
        for (const std::exception_ptr& e : errors)
            if (e) std::rethrow_exception(e);
    }
    const double assemblySeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - assemblyStart).count();
    LevelCookResult result;
    if (isPemList(list)) {
        result.warnings = installPemShards(dir, list, *scene);
        if (log)
            for (const std::string& w : result.warnings)
                *log << "warning: " << w << '\n';
        result.index = (fs::path(dir) / kPemFolder / "manifest.json").string();
        result.probes.push_back({kPemFolder, kPemFolder, true, "merged", 0.0});
    } else {
        installLevel(dir, list, result, log);
    }
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    writeTime(mergeTimePath(dir), "merge", result.seconds, "merge", assemblySeconds);
    return result;
}

} // namespace specula
