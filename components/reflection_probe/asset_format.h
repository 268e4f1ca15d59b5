#pragma once
// Which version of an asset format a manifest is written in, and what a reader does with it.
// Every manifest opens with "format": {"name", "major", "minor"} (docs/formats.md). A reader
// accepts its own major with any minor: a newer minor only adds members, which it ignores and
// lists once in a warning (engine/core/warning.h). A higher major is refused ("re-cook or
// update"), a lower one names the command that re-cooks it. Manifests written before the
// format had a minor ("format": "specula-probe", "version": 2) read as MAJOR.0.
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace specula {

struct AssetFormat {
    std::string_view name; // "specula-probe", "specula-level"
    int major = 0, minor = 0;
    std::string_view schema; // docs/formats/<schema>.schema.json, "" when chosen per flavour
};

// Probe manifests, every flavour. 2.0: KTX2 textures (1 stored OpenEXR). 2.1: the format
// object, the seal, RGBA16F object layers.
inline constexpr AssetFormat kProbeFormat{"specula-probe", 2, 1, ""};
// Level indices (level.json). 1.1: the format object.
inline constexpr AssetFormat kLevelFormat{"specula-level", 1, 1, "level"};

struct FormatVersion {
    int major = 0, minor = 0;
};

// {"name": ..., "major": ..., "minor": ...}, the "format" member a writer stores.
nlohmann::json formatJson(const AssetFormat& format);

// The format name a manifest states ("format" as an object's "name" or, before 2.1, as a
// string); nullopt when it states none.
std::optional<std::string> assetFormatName(const nlohmann::json& manifest);

// The version `manifest` is written in, when it is `expected.name` with expected.major.
// Throws Error(file, "format" / "format.major" / "version", ...) otherwise: another format, a
// newer major ("asset format 3.1 is newer than this runtime (2.x): re-cook or update"), an
// older one (naming what it stored and `specula-cook bake`).
FormatVersion readAssetFormat(const nlohmann::json& manifest, const AssetFormat& expected,
                              const std::string& file);

// When `found` is a newer minor than `runtime` and `manifest` holds members that
// docs/formats/<schema>.schema.json does not declare, warns once, naming the file, both
// versions and every such member (what this runtime ignores). Nothing otherwise.
void warnAboutNewerMinor(const nlohmann::json& manifest, const AssetFormat& runtime,
                         FormatVersion found, std::string_view schema, const std::string& file);

} // namespace specula
