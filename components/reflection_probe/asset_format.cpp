#include "asset_format.h"

#include "components/reflection_probe/manifest_schema.h"
#include "engine/core/error.h"
#include "engine/core/warning.h"

namespace specula {

using nlohmann::json;

namespace {

std::string versionText(FormatVersion v) {
    return std::to_string(v.major) + "." + std::to_string(v.minor);
}

// An integer member of the format object in 0 .. 1e6 (a version, never a float or a string).
int versionMember(const json& format, const char* key, const std::string& file) {
    const auto it = format.find(key);
    if (it == format.end() || !it->is_number_integer() || it->get<long long>() < 0 ||
        it->get<long long>() > 1000000)
        throw Error(file, std::string("format.") + key, "expected an integer 0 .. 1000000");
    return it->get<int>();
}

// Manifests written before 2.1 (probes) and 1.1 (levels): "format" a string and an integer
// "version", which was the major.
FormatVersion legacyVersion(const json& m, const std::string& file) {
    const auto it = m.find("version");
    if (it == m.end() || !it->is_number_integer() || it->get<long long>() < 0 ||
        it->get<long long>() > 1000000)
        throw Error(file, "version", "expected the format's integer version");
    return {it->get<int>(), 0};
}

} // namespace

json formatJson(const AssetFormat& format, bool newest) {
    const bool plain = !newest && format.plainVersion.major > 0;
    const FormatVersion v = plain ? format.plainVersion : FormatVersion{format.major, format.minor};
    return {{"name", std::string(format.name)}, {"major", v.major}, {"minor", v.minor}};
}

std::optional<std::string> assetFormatName(const json& m) {
    const auto it = m.is_object() ? m.find("format") : m.end();
    if (it == m.end()) return std::nullopt;
    if (it->is_string()) return it->get<std::string>();
    if (it->is_object() && it->contains("name") && (*it)["name"].is_string())
        return (*it)["name"].get<std::string>();
    return std::nullopt;
}

FormatVersion readAssetFormat(const json& m, const AssetFormat& expected, const std::string& file) {
    if (assetFormatName(m) != std::string(expected.name))
        throw Error(file, "format",
                    "expected {\"name\": \"" + std::string(expected.name) +
                        "\", \"major\", \"minor\"} (this is no " + std::string(expected.name) +
                        " manifest)");
    const json& format = m["format"];
    const bool legacy = format.is_string();
    const FormatVersion found = legacy ? legacyVersion(m, file)
                                       : FormatVersion{versionMember(format, "major", file),
                                                       versionMember(format, "minor", file)};
    const std::string field = legacy ? "version" : "format.major";
    const std::string runtime = std::to_string(expected.major) + ".x";
    if (found.major > expected.major)
        throw Error(file, field,
                    "asset format " + versionText(found) + " is newer than this runtime (" +
                        runtime +
                        "): re-cook it with this release's `specula-cook bake`, or "
                        "update the runtime");
    const int oldest = expected.oldestMajor > 0 ? expected.oldestMajor : expected.major;
    if (found.major < oldest) {
        // Probe format 1 stored its textures as OpenEXR, which only the tools could read.
        const std::string what = expected.name == kProbeFormat.name && found.major == 1
                                     ? " (OpenEXR textures; this runtime reads KTX2)"
                                     : "";
        throw Error(file, field,
                    "asset format " + versionText(found) + what + " is older than this runtime (" +
                        runtime + "): re-cook it with `specula-cook bake`");
    }
    return found;
}

void warnAboutNewerMinor(const json& manifest, const AssetFormat& runtime, FormatVersion found,
                         std::string_view schema, const std::string& file) {
    if (found.major != runtime.major || found.minor <= runtime.minor) return;
    const std::vector<std::string> ignored = undeclaredMembers(manifest, schema);
    if (ignored.empty()) return; // a newer minor only adds members: none here, nothing lost
    std::string message = file + ": asset format " + versionText(found) +
                          " is newer than this runtime (" +
                          versionText({runtime.major, runtime.minor}) +
                          "); it reads the asset without the members it does not know:";
    for (std::size_t i = 0; i < ignored.size(); ++i)
        message += (i ? ", " : " ") + ignored[i];
    warn(message);
}

} // namespace specula
