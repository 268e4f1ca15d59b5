#include "assetcooker/lib/farm/shard_install.h"

#include "components/reflection_probe/manifest_fields.h"
#include "components/reflection_probe/writer/probe_folder.h"
#include "engine/core/error.h"

namespace specula {

namespace fs = std::filesystem;

namespace {

// `to` holds the same files as `from`: hard links where the file system allows (a light field
// at the paper's size is ~300 MB a probe, which merge would otherwise copy), copies where it
// does not (another file system). Safe because nothing writes a cooked file in place: every
// writer writes beside and renames, which unlinks the level's name and leaves the store's.
void linkOrCopyTree(const fs::path& from, const fs::path& to) {
    if (fs::is_directory(from)) {
        fs::create_directory(to);
        for (const fs::directory_entry& f : fs::directory_iterator(from))
            linkOrCopyTree(f.path(), to / f.path().filename());
        return;
    }
    std::error_code ec;
    fs::create_hard_link(from, to, ec);
    if (ec) fs::copy_file(from, to);
}

} // namespace

// DIR/<folder> replaced atomically by the store's shard folder (linked or copied).
void installShard(const fs::path& from, const fs::path& to, const std::string& scene) {
    writeProbeFolder(to.string(), scene, [&](const fs::path& tmp) {
        for (const fs::directory_entry& f : fs::directory_iterator(from))
            if (f.path().filename() != "manifest.json")
                linkOrCopyTree(f.path(), tmp / f.path().filename());
        const std::string manifest = (from / "manifest.json").string();
        return parseManifestJson(readManifestText(manifest), manifest);
    });
}

EmbreeScene environmentOf(ProbeScene& scene) {
    return EmbreeScene(scene.registry,
                       [&](ecs::Entity e) { return scene.markup.mirrorEntities.count(e) == 0; });
}

// Error unless the scene still holds what the list planned shard `index`'s probe from: a
// shard computed from an edited scene would be stored under the old hash and merged as if it
// were current. Only geometry and sky are compared: the settings are the list's own.
void checkSceneUnchanged(const std::string& dir, const ShardList& list, int index,
                         ProbeScene& scene, const EmbreeScene& environment) {
    const LevelProbeEntry& planned =
        list.level.probes[std::size_t(list.shards[std::size_t(index)].probe)];
    const ProbeInputs now = levelProbeInputs(scene, environment, planned.volume, "");
    const char* changed = now.geometry != planned.inputs.geometry ? "the geometry"
                          : now.sky != planned.inputs.sky         ? "the sky"
                                                                  : nullptr;
    if (changed)
        throw Error(shardListPath(dir), "scene",
                    list.scene + " changed since the shard list was written (" + changed +
                        " within reach of probe " + planned.volume.name + ", shard " +
                        std::to_string(index) +
                        "); run specula-cook shards again (nothing was baked)");
}

} // namespace specula
