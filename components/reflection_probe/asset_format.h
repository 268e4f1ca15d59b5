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

struct FormatVersion {
    int major = 0, minor = 0;
};

struct AssetFormat {
    std::string_view name; // "specula-probe", "specula-level"
    int major = 0, minor = 0;
    std::string_view schema; // docs/formats/<schema>.schema.json, "" when chosen per flavour
    // The oldest major this runtime still reads (0: only `major`): a new major that only adds
    // what an older runtime must not misread keeps reading the assets written before it.
    int oldestMajor = 0;
    // The version a writer states when the asset uses nothing of the newest major (0.0: the
    // newest), so runtimes of the older major keep reading it.
    FormatVersion plainVersion{};
};

// Probe manifests, every flavour. 2.0: KTX2 textures (1 stored OpenEXR). 2.1: the format
// object, the seal, RGBA16F object layers. 3.0: compressed distance probes ("compression":
// "bc6h"; the composite's radiance in BC6H, its distance in a file of its own), which a 2.x
// runtime refuses as newer instead of misreading; every other probe is still written as 2.x.
// 2.2 / 3.1: "inputs", the checksums of what the cooker baked the probe from. 3.2: compressed
// PEM probes ("compression": "bc6h", every sample map BC6H; a 3.1 runtime ignores the member and
// reads the maps through its KTX2 reader's BC6H decoder).
inline constexpr AssetFormat kProbeFormat{"specula-probe", 3, 2, "", 2, {2, 2}};
// Level indices (level.json). 1.1: the format object.
inline constexpr AssetFormat kLevelFormat{"specula-level", 1, 1, "level"};

// {"name": ..., "major": ..., "minor": ...}, the "format" member a writer stores: `format`'s
// newest version, or its plainVersion when the asset uses nothing newer (`newest` false).
nlohmann::json formatJson(const AssetFormat& format, bool newest = true);

// The format name a manifest states ("format" as an object's "name" or, before 2.1, as a
// string); nullopt when it states none.
std::optional<std::string> assetFormatName(const nlohmann::json& manifest);

// The version `manifest` is written in, when it is `expected.name` with a major from
// expected.oldestMajor to expected.major. Throws Error(file, "format" / "format.major" /
// "version", ...) otherwise: another format, a newer major ("asset format 4.1 is newer than
// this runtime (3.x): re-cook or update"), an older one (naming what it stored and
// `specula-cook bake`).
FormatVersion readAssetFormat(const nlohmann::json& manifest, const AssetFormat& expected,
                              const std::string& file);

// When `found` is a newer minor than `runtime` and `manifest` holds members that
// docs/formats/<schema>.schema.json does not declare, warns once, naming the file, both
// versions and every such member (what this runtime ignores). Nothing otherwise.
void warnAboutNewerMinor(const nlohmann::json& manifest, const AssetFormat& runtime,
                         FormatVersion found, std::string_view schema, const std::string& file);

} // namespace specula
