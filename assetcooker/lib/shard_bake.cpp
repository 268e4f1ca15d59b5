#include "shard_bake.h"

#include "components/reflection_probe/manifest_fields.h"
#include "components/reflection_probe/probe_folder.h"
#include "engine/core/error.h"
#include "engine/core/file_write.h"

#include <chrono>
#include <cmath>
#include <filesystem>

namespace specula {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr int kShardListVersion = 1;

json settingsJson(const DistanceCookSettings& s) {
    const GgxPrefilterOptions& p = s.prefilter;
    return {{"flavour", "distance"},
            {"face_res", s.faceRes},
            {"planned", s.planned},
            {"record_plan", s.recordPlan},
            {"glossy", toString(s.glossy)},
            {"prefilter",
             {{"levels", p.levels},
              {"samples", p.samples},
              {"max_samples", p.maxSamples},
              {"lod_bias", p.lodBias},
              {"d_inf", std::isfinite(p.dInf) ? json(p.dInf) : json(nullptr)}}}};
}

json settingsJson(const LightFieldCookSettings& s) {
    json j = {{"flavour", "lightfield"},
              {"cameras", s.cameras},
              {"image_res", s.imageRes},
              {"compression", s.compression == LightFieldCompression::BC1 ? "bc1" : "none"},
              {"cell_centre", nullptr},
              {"cell_size", nullptr}};
    if (s.cellCentre) j["cell_centre"] = {s.cellCentre->x, s.cellCentre->y, s.cellCentre->z};
    if (s.cellSize) j["cell_size"] = *s.cellSize;
    return j;
}

json settingsJson(const PemCookSettings&) {
    return {{"flavour", "pem"}};
}

// The shard's hash: what its bytes depend on (see shard_bake.h), hexadecimal.
std::string shardHash(const Shard& s, const LevelProbeEntry& e, const json& settings,
                      const ProbeScene& scene) {
    std::string text = "specula-shard " + std::to_string(kShardListVersion) + '\n' + s.kind + ' ' +
                       std::to_string(s.part) + '\n' + e.inputs.geometry + '\n' + e.inputs.options +
                       '\n' + e.inputs.sky + '\n' + settings.dump() + '\n';
    // The effect plan reads the probe's own markup members, whatever its volumes say.
    for (const ProbeMarkup& m : scene.markup.probes)
        if (m.node == e.volume.name) text += m.options.dump();
    std::string hash = bytesChecksum(text.data(), text.size());
    if (const auto colon = hash.find(':'); colon != std::string::npos) hash.erase(0, colon + 1);
    return hash;
}

template <class T>
T member(const json& j, const char* name, const std::string& file, const std::string& field) {
    if (!j.is_object() || !j.contains(name))
        throw Error(file, field + name, "missing from the shard list");
    try {
        return j.at(name).get<T>();
    } catch (const json::exception&) {
        throw Error(file, field + name, "has the wrong type");
    }
}

// A computed shard: its folder holds the probe's manifest (the last file its writer renames in).
bool shardPresent(const std::string& dir, const Shard& s) {
    std::error_code ec;
    return fs::is_regular_file(fs::path(shardStore(dir)) / s.hash / "manifest.json", ec);
}

// {"format": "specula-shard-time", "version": 1, "what": ..., "seconds": ...}, atomically.
void writeTime(const std::string& file, const std::string& what, double seconds) {
    const json doc = {
        {"format", "specula-shard-time"}, {"version", 1}, {"what", what}, {"seconds", seconds}};
    writeFileAtomically(file, doc.dump(2) + "\n");
}

// DIR/<folder> replaced atomically by a copy of the store's shard folder.
void installShard(const fs::path& from, const fs::path& to, const std::string& scene) {
    writeProbeFolder(to.string(), scene, [&](const fs::path& tmp) {
        for (const fs::directory_entry& f : fs::directory_iterator(from))
            if (f.path().filename() != "manifest.json")
                fs::copy(f.path(), tmp / f.path().filename(), fs::copy_options::recursive);
        const std::string manifest = (from / "manifest.json").string();
        return parseManifestJson(readManifestText(manifest), manifest);
    });
}

} // namespace

json cookSettingsToJson(const CookFlavour& flavour) {
    return std::visit([](const auto& s) { return settingsJson(s); }, flavour);
}

CookFlavour cookSettingsFromJson(const json& j, const std::string& file) {
    const std::string flavour = member<std::string>(j, "flavour", file, "settings.");
    if (flavour == "distance") {
        DistanceCookSettings s;
        s.faceRes = member<int>(j, "face_res", file, "settings.");
        s.planned = member<bool>(j, "planned", file, "settings.");
        s.recordPlan = member<bool>(j, "record_plan", file, "settings.");
        const std::string glossy = member<std::string>(j, "glossy", file, "settings.");
        s.glossy = glossy == "on"    ? GlossyBake::On
                   : glossy == "off" ? GlossyBake::Off
                                     : GlossyBake::Auto;
        const json& p = j.at("prefilter");
        s.prefilter.levels = member<int>(p, "levels", file, "settings.prefilter.");
        s.prefilter.samples = member<int>(p, "samples", file, "settings.prefilter.");
        s.prefilter.maxSamples = member<int>(p, "max_samples", file, "settings.prefilter.");
        s.prefilter.lodBias = member<float>(p, "lod_bias", file, "settings.prefilter.");
        if (p.contains("d_inf") && !p["d_inf"].is_null())
            s.prefilter.dInf = member<float>(p, "d_inf", file, "settings.prefilter.");
        return s;
    }
    if (flavour == "lightfield") {
        LightFieldCookSettings s;
        s.cameras = member<int>(j, "cameras", file, "settings.");
        s.imageRes = member<int>(j, "image_res", file, "settings.");
        s.compression = member<std::string>(j, "compression", file, "settings.") == "bc1"
                            ? LightFieldCompression::BC1
                            : LightFieldCompression::None;
        if (j.contains("cell_centre") && !j["cell_centre"].is_null())
            s.cellCentre = probeVec3(j["cell_centre"], file, "settings.cell_centre");
        if (j.contains("cell_size") && !j["cell_size"].is_null())
            s.cellSize = member<float>(j, "cell_size", file, "settings.");
        return s;
    }
    throw Error(file, "settings.flavour",
                "expected distance or lightfield (a level's flavours), got '" + flavour + "'");
}

std::string shardStore(const std::string& dir) {
    return (fs::path(dir) / ".shards").string();
}

std::string shardListPath(const std::string& dir) {
    return (fs::path(shardStore(dir)) / "shards.json").string();
}

ShardList writeShardList(ProbeScene& scene, const LevelCookOptions& options, std::ostream* log) {
    const LevelPlan plan = planLevel(scene, options, log);
    ShardList list;
    list.scene = scene.path;
    list.sky = scene.skyPath;
    list.settings = cookSettingsToJson(options.cook.flavour);
    list.level = plan.index;
    json shards = json::array();
    for (std::size_t i = 0; i < list.level.probes.size(); ++i) {
        LevelProbeEntry& e = list.level.probes[i];
        e.manifestChecksum.clear(); // known once merged
        Shard s;
        s.probe = int(i);
        s.hash = shardHash(s, e, list.settings, scene);
        shards.push_back(
            {{"kind", s.kind}, {"probe", s.probe}, {"part", s.part}, {"hash", s.hash}});
        list.shards.push_back(s);
    }
    const json doc = {{"format", "specula-shards"},
                      {"version", kShardListVersion},
                      {"scene", list.scene},
                      {"sky", list.sky},
                      {"settings", list.settings},
                      {"level", toJson(list.level)},
                      {"shards", shards}};
    fs::create_directories(shardStore(options.cook.out));
    writeFileAtomically(shardListPath(options.cook.out), doc.dump(2) + "\n");
    return list;
}

std::string shardTimePath(const std::string& dir, const Shard& s) {
    return (fs::path(shardStore(dir)) / (s.hash + ".time.json")).string();
}

std::string mergeTimePath(const std::string& dir) {
    return (fs::path(shardStore(dir)) / "merge.time.json").string();
}

ShardList readShardList(const std::string& dir) {
    const std::string file = shardListPath(dir);
    std::error_code ec;
    if (!fs::is_regular_file(file, ec))
        throw Error(file, "",
                    "missing: no shard list (run specula-cook shards SCENE --out " + dir +
                        " first)");
    const json doc = parseManifestJson(readManifestText(file), file);
    if (!doc.is_object() || doc.value("format", "") != "specula-shards" ||
        doc.value("version", 0) != kShardListVersion)
        throw Error(file, "format",
                    "expected a specula-shards list of version " +
                        std::to_string(kShardListVersion));
    ShardList list;
    list.scene = member<std::string>(doc, "scene", file, "");
    list.sky = member<std::string>(doc, "sky", file, "");
    list.settings = doc.at("settings");
    cookSettingsFromJson(list.settings, file); // validated here, before any work
    list.level = levelIndexFromJson(doc.at("level"), file);
    const json& shards = doc.at("shards");
    if (!shards.is_array()) throw Error(file, "shards", "expected an array");
    for (std::size_t i = 0; i < shards.size(); ++i) {
        const std::string field = "shards[" + std::to_string(i) + "].";
        Shard s;
        s.kind = member<std::string>(shards[i], "kind", file, field);
        s.probe = member<int>(shards[i], "probe", file, field);
        s.part = member<int>(shards[i], "part", file, field);
        s.hash = member<std::string>(shards[i], "hash", file, field);
        if (s.kind != "probe" || s.part != 0 || s.probe < 0 ||
            std::size_t(s.probe) >= list.level.probes.size())
            throw Error(file, field + "probe", "expected a probe shard of the level's probes");
        if (s.hash.empty() || s.hash.find_first_of("/\\.") != std::string::npos)
            throw Error(file, field + "hash", "expected a content hash");
        list.shards.push_back(s);
    }
    return list;
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
    outcome.folder = (fs::path(shardStore(dir)) / s.hash).string();
    if (shardPresent(dir, s)) {
        outcome.skipped = true;
        return outcome;
    }
    const auto start = std::chrono::steady_clock::now();
    ProbeScene scene(list.scene, list.sky);
    LevelCookOptions level;
    level.cook.scene = list.scene;
    level.cook.sky = list.sky;
    level.cook.flavour = cookSettingsFromJson(list.settings, shardListPath(dir));
    const CookOptions o = levelProbeCookOptions(
        scene, level, list.level.probes[std::size_t(s.probe)], outcome.folder);
    cookProbe(scene, o, log);
    outcome.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    writeTime(shardTimePath(dir, s),
              "shard " + std::to_string(index) + " (probe " +
                  list.level.probes[std::size_t(s.probe)].volume.name + ")",
              outcome.seconds);
    return outcome;
}

LevelCookResult mergeShards(const std::string& dir, std::ostream* log) {
    const auto start = std::chrono::steady_clock::now();
    ShardList list = readShardList(dir);
    std::string missing;
    std::size_t missingCount = 0;
    for (std::size_t i = 0; i < list.shards.size(); ++i)
        if (!shardPresent(dir, list.shards[i])) {
            const Shard& s = list.shards[i];
            missing += (missing.empty() ? "" : ", ") + std::to_string(i) + " (probe " +
                       list.level.probes[std::size_t(s.probe)].volume.name + ", " + s.hash + ")";
            ++missingCount;
        }
    if (missingCount > 0)
        throw Error(shardListPath(dir), "shards",
                    std::to_string(missingCount) + " of " + std::to_string(list.shards.size()) +
                        " shards not baked: " + missing +
                        "; run specula-cook bake-shard for each (nothing was merged)");
    LevelPlan plan; // the previous index, for the probes no longer in the level
    std::error_code ec;
    if (fs::is_regular_file(fs::path(dir) / "level.json", ec)) try {
            plan.previous = readLevelIndex((fs::path(dir) / "level.json").string());
        } catch (const Error&) {
        }
    LevelCookResult result;
    for (const Shard& s : list.shards) {
        LevelProbeEntry& e = list.level.probes[std::size_t(s.probe)];
        const fs::path to = fs::path(dir) / e.folder;
        installShard(fs::path(shardStore(dir)) / s.hash, to, list.scene);
        e.manifestChecksum = fileChecksum((to / "manifest.json").string());
        result.probes.push_back({e.volume.name, e.folder, true, "merged", 0.0});
    }
    result.index = (fs::path(dir) / "level.json").string();
    writeLevelIndex(list.level, result.index);
    plan.index = list.level;
    warnOfDroppedProbes(plan, dir, result.warnings, log);
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    writeTime(mergeTimePath(dir), "merge", result.seconds);
    return result;
}

} // namespace specula
