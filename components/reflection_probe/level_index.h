#pragma once
// A baked level's index, DIR/level.json: every probe's volumes (probe_volume.h), the folder
// its cooked asset lies in, that asset's manifest checksum, and the checksums of the inputs
// it was baked from (so a re-bake knows which probes are stale and why). Written by
// `specula-cook bake` when a scene has several probes; read by whatever loads the level.
//
//   {"format": {"name": "specula-level", "major": 1, "minor": 1}, "source": "scene.gltf",
//    "flavour": "distance",
//    "probes": [{"name": .., "position": [..], "proxy": {..}, "influence": {..},
//                "blend_distance": .., "priority": .., "cell_size": .., "folder": "name",
//                "manifest_checksum": "fnv1a64:..",
//                "inputs": {"geometry": "fnv1a64:..", "options": "..", "sky": ".."}}]}
#include "components/reflection_probe/manifest_fields.h"
#include "components/reflection_probe/probe_volume.h"

#include <string>
#include <vector>

namespace specula {

struct LevelProbeEntry {
    ProbeVolume volume;
    std::string folder; // relative to the level folder
    std::string manifestChecksum;
    ProbeInputs inputs;
};

struct LevelIndex {
    std::string source;  // the scene, as given to the bake
    std::string flavour; // of every probe
    std::vector<LevelProbeEntry> probes;
};

nlohmann::json toJson(const LevelIndex& index);
// Throws Error naming `file` and the field when it is no level index of this version (any
// flavour: a farm's shard list holds a PEM one).
LevelIndex levelIndexFromJson(const nlohmann::json& j, const std::string& file);
// DIR/level.json read and parsed (readManifestText's limits), its flavour distance or
// lightfield; throws Error naming the file and the field.
LevelIndex readLevelIndex(const std::string& path);
// Written atomically (writeFileAtomically): a reader sees the old index or the new one.
void writeLevelIndex(const LevelIndex& index, const std::string& path);

} // namespace specula
