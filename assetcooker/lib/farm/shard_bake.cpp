#include "assetcooker/lib/farm/shard_bake.h"
#include "assetcooker/lib/farm/shard_compute.h"

#include "assetcooker/lib/farm/shard_checksum.h"
#include "assetcooker/lib/farm/shard_install.h"
#include "assetcooker/lib/flavours/pem/shard_pem.h"

#include "components/reflection_probe/manifest_fields.h"
#include "components/reflection_probe/writer/probe_folder.h"
#include "engine/core/error.h"
#include "engine/core/file_write.h"

#include <algorithm>
#include <chrono>
#include <filesystem>

namespace specula {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr int kShardListVersion = 3; // 2: light-field part shards, shard_rows; 3: PEM shards

// The shard's hash: what its bytes depend on (see shard_bake.h), hexadecimal.
std::string shardHash(const Shard& s, const LevelProbeEntry& e, const json& settings,
                      const ProbeScene& scene, int shardRows) {
    std::string text = "specula-shard " + std::to_string(kShardListVersion) + '\n' + s.kind + ' ' +
                       std::to_string(s.part) + '\n' + e.inputs.geometry + '\n' + e.inputs.options +
                       '\n' + e.inputs.sky + '\n' + settings.dump() + '\n';
    // A part's bytes depend on the rows it covers; the probe's do not.
    if (s.kind == kLightFieldRowsShard) text += "rows " + std::to_string(shardRows) + '\n';
    // The effect plan reads the probe's own markup members, whatever its volumes say.
    for (const ProbeMarkup& m : scene.markup.probes)
        if (m.node == e.volume.name) text += m.options.dump();
    std::string hash = bytesChecksum(text.data(), text.size());
    if (const auto colon = hash.find(':'); colon != std::string::npos) hash.erase(0, colon + 1);
    return hash;
}

int blocksPerSlab(int cameras, int rows) {
    return (cameras + rows - 1) / rows;
}

// The part's slab and rows from its index and the list's rows a part.
void setPartRows(Shard& s, int cameras, int rows) {
    const int blocks = blocksPerSlab(cameras, rows);
    s.slab = s.part / blocks;
    s.j0 = (s.part % blocks) * rows;
    s.j1 = std::min(cameras, s.j0 + rows);
}

int listCameras(const ShardList& list) {
    return list.settings.value("cameras", 0);
}

} // namespace

void writeTime(const std::string& file, const std::string& what, double seconds,
               const std::string& by, double assemblySeconds) {
    json doc = {{"format", "specula-shard-time"},
                {"version", 1},
                {"what", what},
                {"seconds", seconds},
                {"by", by}};
    if (assemblySeconds >= 0) doc["assembly_seconds"] = assemblySeconds;
    writeFileAtomically(file, doc.dump(2) + "\n");
}

ShardList writeShardList(ProbeScene& scene, const LevelCookOptions& options, std::ostream* log,
                         int shardRows) {
    ShardList list;
    if (const auto* lf = std::get_if<LightFieldCookSettings>(&options.cook.flavour)) {
        if (shardRows < 0 || shardRows > lf->cameras)
            throw Error(shardListPath(options.cook.out), "shard_rows",
                        "expected 1 .. " + std::to_string(lf->cameras) +
                            " (the cameras a slab side), got " + std::to_string(shardRows));
        list.shardRows = shardRows == 0 ? lf->cameras : shardRows;
    }
    list.scene = scene.path;
    list.sky = scene.skyPath;
    list.settings = cookSettingsToJson(options.cook.flavour);
    json shards = json::array();
    auto add = [&](Shard s, const LevelProbeEntry& e) {
        s.hash = shardHash(s, e, list.settings, scene, list.shardRows);
        shards.push_back(
            {{"kind", s.kind}, {"probe", s.probe}, {"part", s.part}, {"hash", s.hash}});
        list.shards.push_back(s);
    };
    const int cameras = listCameras(list);
    if (std::holds_alternative<PemCookSettings>(options.cook.flavour)) {
        planPemShards(scene, options.cook, list);
        const std::vector<Shard> planned = std::move(list.shards);
        list.shards.clear();
        for (const Shard& s : planned)
            add(s, list.level.probes.front());
    } else {
        list.level = planLevel(scene, options, log).index;
    }
    for (std::size_t i = 0; i < list.level.probes.size() && !isPemList(list); ++i) {
        LevelProbeEntry& e = list.level.probes[i];
        e.manifestChecksum.clear(); // known once merged
        if (list.shardRows > 0)
            for (int part = 0; part < 6 * blocksPerSlab(cameras, list.shardRows); ++part) {
                Shard s;
                s.kind = kLightFieldRowsShard;
                s.probe = int(i);
                s.part = part;
                setPartRows(s, cameras, list.shardRows);
                add(s, e);
            }
        Shard s;
        s.probe = int(i);
        add(s, e);
    }
    const json doc = {{"format", "specula-shards"},  {"version", kShardListVersion},
                      {"scene", list.scene},         {"sky", list.sky},
                      {"settings", list.settings},   {"shard_rows", list.shardRows},
                      {"level", toJson(list.level)}, {"shards", shards}};
    fs::create_directories(shardStore(options.cook.out));
    writeFileAtomically(shardListPath(options.cook.out), doc.dump(2) + "\n");
    return list;
}

ShardList readShardList(const std::string& dir) {
    const std::string file = shardListPath(dir);
    std::error_code ec;
    if (!fs::is_regular_file(file, ec))
        throw Error(file, "",
                    "missing: no shard list (run specula-cook shards SCENE --out " + dir +
                        " first)");
    return shardListFromJson(parseManifestJson(readManifestText(file), file), file);
}

ShardList shardListFromJson(const json& doc, const std::string& file) {
    if (!doc.is_object() || !doc.contains("format") || !doc["format"].is_string() ||
        !doc.contains("version") || !doc["version"].is_number_integer() ||
        doc.value("format", "") != "specula-shards" || doc.value("version", 0) != kShardListVersion)
        throw Error(file, "format",
                    "expected a specula-shards list of version " +
                        std::to_string(kShardListVersion));
    const auto member = [&](const char* key) -> const json& {
        if (!doc.contains(key)) throw Error(file, key, "missing");
        return doc[key];
    };
    ShardList list;
    list.scene = jsonMember<std::string>(doc, "scene", file, "");
    list.sky = jsonMember<std::string>(doc, "sky", file, "");
    list.settings = member("settings");
    const CookFlavour flavour = cookSettingsFromJson(list.settings, file); // validated here
    list.shardRows = jsonMember<int>(doc, "shard_rows", file, "");
    const int cameras = listCameras(list);
    const bool lightField = std::holds_alternative<LightFieldCookSettings>(flavour);
    if (lightField ? list.shardRows < 1 || list.shardRows > cameras : list.shardRows != 0)
        throw Error(file, "shard_rows",
                    lightField ? "expected 1 .. " + std::to_string(cameras) : "expected 0");
    list.level = levelIndexFromJson(member("level"), file);
    const json& shards = member("shards");
    if (!shards.is_array()) throw Error(file, "shards", "expected an array");
    for (std::size_t i = 0; i < shards.size(); ++i) {
        const std::string field = "shards[" + std::to_string(i) + "].";
        Shard s;
        s.kind = jsonMember<std::string>(shards[i], "kind", file, field);
        s.probe = jsonMember<int>(shards[i], "probe", file, field);
        s.part = jsonMember<int>(shards[i], "part", file, field);
        s.hash = jsonMember<std::string>(shards[i], "hash", file, field);
        if (s.probe < 0 || std::size_t(s.probe) >= list.level.probes.size())
            throw Error(file, field + "probe", "expected an index of the level's probes");
        if (s.kind == kLightFieldRowsShard && lightField) {
            if (s.part < 0 || s.part >= 6 * blocksPerSlab(cameras, list.shardRows))
                throw Error(file, field + "part",
                            "expected 0 .. " +
                                std::to_string(6 * blocksPerSlab(cameras, list.shardRows) - 1));
            setPartRows(s, cameras, list.shardRows);
        } else if (isPemList(list)) {
            if (s.kind != kPemTraceShard && s.kind != kPemSampleShard)
                throw Error(file, field + "kind", "expected pem-trace or pem-sample");
            if (s.part < 0 || s.part >= pemListSamples(list))
                throw Error(file, field + "part",
                            "expected a sample 0 .. " + std::to_string(pemListSamples(list) - 1));
        } else if (s.kind != kProbeShard || s.part != 0) {
            throw Error(file, field + "kind",
                        std::string("expected a probe shard (part 0)") +
                            (lightField ? " or a lightfield-rows part" : ""));
        }
        if (s.hash.empty() || s.hash.find_first_of("/\\.") != std::string::npos)
            throw Error(file, field + "hash", "expected a content hash");
        list.shards.push_back(s);
    }
    // A list without a probe, or a probe (a PEM sample) without its shards, would merge into
    // a level whose entries have no asset and no checksums behind them.
    if (list.level.probes.empty())
        throw Error(file, "level.probes", "the level has no probe: nothing to bake or merge");
    if (isPemList(list)) {
        // Found by position: the traces, then the samples (pemShardIndex).
        const int samples = pemListSamples(list);
        for (int k = 0; k < 2 * samples; ++k) {
            const char* kind = k < samples ? kPemTraceShard : kPemSampleShard;
            if (std::size_t(k) >= list.shards.size() || list.shards[std::size_t(k)].kind != kind ||
                list.shards[std::size_t(k)].part != k % samples)
                throw Error(file, "shards[" + std::to_string(k) + "]",
                            std::string("expected the ") + kind + " shard of sample " +
                                std::to_string(k % samples) + " (run specula-cook shards again)");
        }
        if (list.shards.size() != std::size_t(2 * samples))
            throw Error(file, "shards",
                        "expected " + std::to_string(2 * samples) +
                            " shards (run specula-cook "
                            "shards again)");
    }
    for (std::size_t i = 0; i < list.level.probes.size(); ++i)
        if (std::ranges::none_of(list.shards, [&](const Shard& s) {
                return s.probe == int(i) && (s.kind == kProbeShard || isPemList(list));
            }))
            throw Error(file, "shards",
                        "no shard bakes probe " + list.level.probes[i].volume.name +
                            " (run specula-cook shards again)");
    return list;
}

namespace {

LevelCookOptions shardLevelOptions(const std::string& dir, const ShardList& list) {
    LevelCookOptions level;
    level.cook.scene = list.scene;
    level.cook.sky = list.sky;
    level.cook.flavour = cookSettingsFromJson(list.settings, shardListPath(dir));
    level.cook.progress = false;
    return level;
}

// Error naming the parts of probe shard `index` the store lacks.
void checkPartsPresent(const std::string& dir, const ShardList& list, int index) {
    const std::vector<int> deps = shardDependencies(list, index);
    std::string missing;
    std::size_t missingCount = 0;
    for (const int d : deps)
        if (!shardPresent(dir, list.shards[std::size_t(d)])) {
            missing += (missing.empty() ? "" : ", ") + std::to_string(d) + " (" +
                       shardLabel(list, d) + ", " + list.shards[std::size_t(d)].hash + ")";
            ++missingCount;
        }
    if (missingCount > 0)
        throw Error(shardListPath(dir), "shards",
                    "shard " + std::to_string(index) + " (" + shardLabel(list, index) +
                        (list.shards[std::size_t(index)].kind == kProbeShard ? ") assembles "
                                                                             : ") reads ") +
                        std::to_string(deps.size()) +
                        (list.shards[std::size_t(index)].kind == kProbeShard ? " part shards; "
                                                                             : " trace shards; ") +
                        std::to_string(missingCount) + " not baked: " + missing +
                        "; run specula-cook bake-shard for each");
}

// The parts of probe shard `index`, read from the store; Error naming the missing ones or
// the malformed part file.
std::vector<LightFieldRows> readParts(const std::string& dir, const ShardList& list, int index) {
    checkPartsPresent(dir, list, index);
    const std::vector<int> deps = shardDependencies(list, index);
    const int cameras = listCameras(list);
    const int res = list.settings.value("image_res", 0);
    std::vector<LightFieldRows> blocks;
    for (const int d : deps) {
        const Shard& p = list.shards[std::size_t(d)];
        blocks.push_back(
            readLightFieldRows(shardOutputPath(dir, p), p.slab, p.j0, p.j1, cameras, res));
    }
    return blocks;
}

} // namespace

// Computes shard `index` (not in the store) on `scene`: a part's block, or a probe's folder
// (a light-field probe's assembled from its parts).
void computeShard(const std::string& dir, const ShardList& list, int index, ProbeScene& scene,
                  std::ostream* log) {
    const Shard& s = list.shards[std::size_t(index)];
    if (isPemList(list)) return computePemShard(dir, list, index, scene);
    const LevelCookOptions level = shardLevelOptions(dir, list);
    CookOptions o = levelProbeCookOptions(scene, level, list.level.probes[std::size_t(s.probe)],
                                          shardOutputPath(dir, s));
    if (s.kind == kLightFieldRowsShard) {
        LightFieldBakeOptions b =
            lightFieldBakeOptions(scene, o, std::get<LightFieldCookSettings>(o.flavour));
        // A signal (scancel) stops the trace between rows: nothing reaches the store.
        b.cancelled = [] { return cancelRequested(); };
        LightFieldRows rows;
        try {
            rows = traceLightFieldRows(scene.registry, scene.markup, b, s.slab, s.j0, s.j1);
        } catch (const Error&) {
            throwIfCancelled(o.out);
            throw;
        }
        throwIfCancelled(o.out);
        writeLightFieldRows(rows, o.out);
        return;
    }
    std::vector<LightFieldRows> blocks;
    if (!shardDependencies(list, index).empty()) {
        blocks = readParts(dir, list, index);
        o.lightFieldBlocks = &blocks;
    }
    cookProbe(scene, o, log);
}

std::string timeWhat(const ShardList& list, int index) {
    return "shard " + std::to_string(index) + " (" + shardLabel(list, index) + ")";
}

ShardOutcome bakeShard(const std::string& dir, int index, std::ostream* log) {
    const ShardList list = readShardList(dir);
    if (index < 0 || std::size_t(index) >= list.shards.size())
        throw Error(shardListPath(dir), "shard",
                    "index " + std::to_string(index) + " is out of range: the list has " +
                        std::to_string(list.shards.size()) + " shards (0 .. " +
                        std::to_string(int(list.shards.size()) - 1) + ")");
    const Shard& s = list.shards[std::size_t(index)];
    ShardOutcome outcome;
    outcome.folder = shardOutputPath(dir, s);
    // A shard without its checksums (killed before they were written) is baked again.
    if (shardPresent(dir, s) && shardSumPresent(dir, s)) {
        outcome.skipped = true;
        return outcome;
    }
    const auto start = std::chrono::steady_clock::now();
    // A shard's dependencies are checked before the scene is loaded: a missing one fails fast.
    if (!shardDependencies(list, index).empty()) {
        checkPartsPresent(dir, list, index);
        for (const int d : shardDependencies(list, index))
            verifyShard(dir, list, d); // what it reads is what was baked
    }
    ProbeScene scene(list.scene, list.sky);
    checkSceneUnchanged(dir, list, index, scene, environmentOf(scene));
    computeShard(dir, list, index, scene, log);
    writeShardSum(dir, s);
    outcome.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    writeTime(shardTimePath(dir, s), timeWhat(list, index), outcome.seconds);
    return outcome;
}

} // namespace specula
