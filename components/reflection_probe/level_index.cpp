#include "level_index.h"

#include "components/reflection_probe/asset_format.h"
#include "components/reflection_probe/manifest_fields.h"
#include "engine/core/error.h"
#include "engine/core/file_write.h"

#include <nlohmann/json.hpp>

namespace specula {

using nlohmann::json;

namespace {

std::string stringMember(const json& j, const char* key, const std::string& file,
                         const std::string& field) {
    if (!j.contains(key) || !j[key].is_string())
        throw Error(file, field + key, "expected a string");
    return j[key].get<std::string>();
}

} // namespace

json toJson(const LevelIndex& index) {
    json probes = json::array();
    for (const LevelProbeEntry& e : index.probes) {
        json p = toJson(e.volume);
        p["folder"] = e.folder;
        p["manifest_checksum"] = e.manifestChecksum;
        p["inputs"] = toJson(e.inputs);
        probes.push_back(std::move(p));
    }
    return {{"format", formatJson(kLevelFormat)},
            {"source", index.source},
            {"flavour", index.flavour},
            {"probes", std::move(probes)}};
}

LevelIndex levelIndexFromJson(const json& j, const std::string& file) {
    const FormatVersion version = readAssetFormat(j, kLevelFormat, file);
    LevelIndex index;
    index.source = stringMember(j, "source", file, "");
    index.flavour = stringMember(j, "flavour", file, "");
    if (!j.contains("probes") || !j["probes"].is_array())
        throw Error(file, "probes", "expected an array");
    for (std::size_t i = 0; i < j["probes"].size(); ++i) {
        const json& p = j["probes"][i];
        const std::string field = "probes[" + std::to_string(i) + "]";
        LevelProbeEntry e;
        e.volume = probeVolumeFromJson(p, file, field);
        validateProbeVolume(e.volume, file, field);
        e.folder = stringMember(p, "folder", file, field + ".");
        // A folder is one plain name inside the level: never a path out of it.
        if (e.folder.empty() || e.folder == "." || e.folder == ".." ||
            e.folder.find('/') != std::string::npos || e.folder.find('\\') != std::string::npos)
            throw Error(file, field + ".folder", "expected a folder name inside the level");
        e.manifestChecksum = stringMember(p, "manifest_checksum", file, field + ".");
        if (!p.contains("inputs")) throw Error(file, field + ".inputs", "expected an object");
        e.inputs = probeInputsFromJson(p["inputs"], file, field + ".inputs");
        index.probes.push_back(std::move(e));
    }
    warnAboutNewerMinor(j, kLevelFormat, version, kLevelFormat.schema, file);
    return index;
}

LevelIndex readLevelIndex(const std::string& path) {
    LevelIndex index = levelIndexFromJson(parseManifestJson(readManifestText(path), path), path);
    // A level bakes no PEM (docs/formats/level.schema.json); a farm's shard list does.
    if (index.flavour != "distance" && index.flavour != "lightfield")
        throw Error(path, "flavour",
                    "expected \"distance\" or \"lightfield\", got \"" + index.flavour + "\"");
    return index;
}

void writeLevelIndex(const LevelIndex& index, const std::string& path) {
    writeFileAtomically(path, toJson(index).dump(2) + "\n");
}

} // namespace specula
