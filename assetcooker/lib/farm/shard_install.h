#pragma once
// What the shard commands share about the store (shard_bake.h): installing a computed probe
// shard into the level folder, and checking that a scene still holds what the shard list was
// planned from.
#include "assetcooker/lib/farm/shard_bake.h"

#include <filesystem>
#include <string>

namespace specula {

// DIR/<folder> (`to`) replaced atomically by the store's shard folder `from`: hard links
// where the file system allows, copies where it does not.
void installShard(const std::filesystem::path& from, const std::filesystem::path& to,
                  const std::string& scene);

// The scene's environment without its reflectors, as planLevel traces a probe's reach.
EmbreeScene environmentOf(ProbeScene& scene);

// Throws Error naming DIR's shard list and "scene" unless `scene` still holds the geometry
// and the sky shard `index`'s probe was planned from.
void checkSceneUnchanged(const std::string& dir, const ShardList& list, int index,
                         ProbeScene& scene, const EmbreeScene& environment);

} // namespace specula
