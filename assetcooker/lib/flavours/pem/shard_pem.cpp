#include "assetcooker/lib/flavours/pem/shard_pem.h"

#include "assetcooker/lib/bake/cook.h"
#include "assetcooker/lib/farm/shard_install.h"
#include "assetcooker/lib/flavours/pem/pem_shard_files.h"
#include "components/reflection_probe/pem/pem_asset.h"
#include "components/reflection_probe/pem/writer/pem_compression.h"
#include "components/reflection_probe/pem/writer/pem_probe_writer.h"
#include "components/reflection_probe/writer/probe_folder.h"
#include "engine/core/error.h"
#include "engine/scene/mesh_bounds.h"

#include <filesystem>

namespace specula {

namespace fs = std::filesystem;

namespace {

PemCookSettings listSettings(const std::string& dir, const ShardList& list) {
    return std::get<PemCookSettings>(cookSettingsFromJson(list.settings, shardListPath(dir)));
}

glm::vec3 listCentre(const ShardList& list) {
    return list.level.probes.front().volume.position;
}

// The index of sample k's shard of `kind` (the list holds the traces, then the samples).
int pemShardIndex(const ShardList& list, const char* kind, int k) {
    return (std::string(kind) == kPemTraceShard ? 0 : pemListSamples(list)) + k;
}

std::string traceFile(const std::string& dir, const ShardList& list, int k) {
    return shardOutputPath(dir, list.shards[std::size_t(pemShardIndex(list, kPemTraceShard, k))]);
}

// The decision from every trace's first part (readPemTraceDecisionInputs), as the one-machine
// bake makes it from the whole traces.
PemLocalDecision decideFromTraces(const std::string& dir, const ShardList& list,
                                  const PemCookSettings& s) {
    if (!pemLocalDecisionNeedsTraces(s)) return decidePemLocalLayer(s, std::vector<PemSamples>{});
    std::vector<PemDecisionInputs> inputs;
    for (int k = 0; k < s.samples; ++k)
        inputs.push_back(readPemTraceDecisionInputs(traceFile(dir, list, k)));
    return decidePemLocalLayer(s, inputs, [&] {
        std::vector<glm::vec3> all;
        for (int k = 0; k < s.samples; ++k)
            for (const PemSample& p : readPemTrace(traceFile(dir, list, k)))
                all.push_back(p.x);
        return all;
    });
}

} // namespace

bool isPemList(const ShardList& list) {
    return list.settings.value("flavour", "") == "pem";
}

int pemListSamples(const ShardList& list) {
    return list.settings.value("samples", 0);
}

void planPemShards(ProbeScene& scene, const CookOptions& options, ShardList& list) {
    const PemCookSettings& s = std::get<PemCookSettings>(options.flavour);
    validatePemCookSettings(s, scene.path);
    LevelProbeEntry e;
    e.volume.name = kPemFolder;
    e.volume.position = options.probeCentre
                            ? *options.probeCentre
                            : markupProbeCentre(scene.registry, scene.markup, scene.loaded);
    // Every mesh in reach: the tracer sees the whole scene, and the reflectors move within
    // the cell (parameter "reflector").
    Aabb box = Aabb::cube(e.volume.position, 0.5f * markupCellSize(scene.markup));
    for (ecs::Entity entity : scene.loaded.entities)
        if (scene.registry.has<Mesh>(entity) && scene.registry.has<Transform>(entity))
            box.extend(meshWorldBounds(scene.registry, entity));
    box.min -= glm::vec3(0.01f);
    box.max += glm::vec3(0.01f);
    e.volume.proxy = box;
    e.volume.influence.box = box;
    e.folder = kPemFolder;
    e.inputs = levelProbeInputs(scene, environmentOf(scene), e.volume, list.settings.dump());
    list.level.source = scene.path;
    list.level.flavour = "pem";
    list.level.probes = {e};
    for (const char* kind : {kPemTraceShard, kPemSampleShard})
        for (int k = 0; k < s.samples; ++k) {
            Shard shard;
            shard.kind = kind;
            shard.part = k;
            list.shards.push_back(shard);
        }
}

std::vector<int> pemShardDependencies(const ShardList& list, int index) {
    const Shard& s = list.shards[std::size_t(index)];
    if (s.kind != kPemSampleShard) return {};
    if (list.settings.value("local_layer", "") == "off")
        return {pemShardIndex(list, kPemTraceShard, s.part)};
    std::vector<int> deps;
    for (int k = 0; k < pemListSamples(list); ++k)
        deps.push_back(pemShardIndex(list, kPemTraceShard, k));
    return deps;
}

void computePemShard(const std::string& dir, const ShardList& list, int index, ProbeScene& scene) {
    const Shard& shard = list.shards[std::size_t(index)];
    const PemCookSettings s = listSettings(dir, list);
    const std::string out = shardOutputPath(dir, shard);
    if (shard.kind == kPemTraceShard) {
        PemBake bake(scene, s, listCentre(list), PemBake::Trace);
        // A view without a reflector pixel stores an empty trace: its sample is left out.
        const std::optional<PemSamples> samples = bake.traceAt(bake.parameter(shard.part));
        throwIfCancelled(out); // a signal (scancel) during the trace: nothing reaches the store
        writePemTrace(samples ? *samples : PemSamples{}, out);
        return;
    }
    const PemLocalDecision decision = decideFromTraces(dir, list, s);
    const PemSamples samples = readPemTrace(traceFile(dir, list, shard.part));
    const PemBake bake(scene, s, listCentre(list), PemBake::Infer);
    PemSampleShard result;
    result.sample = shard.part;
    result.decision = decision;
    result.leftOut = samples.empty();
    if (!result.leftOut) result.map = bake.infer(shard.part, samples, decision, nullptr);
    throwIfCancelled(out);
    writePemSampleShard(result, out);
}

std::vector<std::string> installPemShards(const std::string& dir, const ShardList& list,
                                          ProbeScene& scene) {
    const PemCookSettings s = listSettings(dir, list);
    const PemBake bake(scene, s, listCentre(list), PemBake::Infer);
    std::vector<PemSampleMap> maps;
    std::vector<std::string> warnings;
    PemLocalDecision decision;
    for (int k = 0; k < s.samples; ++k) {
        const Shard& shard = list.shards[std::size_t(pemShardIndex(list, kPemSampleShard, k))];
        const std::string file = shardOutputPath(dir, shard);
        PemSampleShard read = readPemSampleShard(file, k, bake.header().distance);
        // Every sample shard decided from the same traces: a different decision is a file
        // of another bake.
        if (k > 0 && !(read.decision == decision))
            throw Error(file, "local",
                        "the local layer differs from sample 0's (a shard of another bake)");
        decision = read.decision;
        if (read.leftOut) {
            warnings.push_back("parameter sample " + std::to_string(k) +
                               " (t = " + std::to_string(bake.parameter(k)) +
                               "): the camera sees no reflector pixel there; the sample is left "
                               "out and the runtime blends its neighbours across it");
            continue;
        }
        read.map.parameter = bake.parameter(k);
        maps.push_back(std::move(read.map));
    }
    if (maps.empty())
        throw Error(shardListPath(dir), "camera",
                    "no parameter sample's view holds a reflector pixel: nothing to infer a map "
                    "from");
    PemAsset asset = bake.assemble(decision, std::move(maps));
    if (s.compression == "bc6h") compressPemMaps(asset); // as the plain bake does
    asset.inputs = cookedProbeInputs(scene, list.settings, asset.centre);
    writePemProbe(asset, (fs::path(dir) / kPemFolder).string(), list.scene);
    return warnings;
}

} // namespace specula
