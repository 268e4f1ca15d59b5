#include "components/reflection_probe/manifest_fields.h"

#include "components/reflection_probe/asset_format.h"
#include "engine/core/error.h"
#include "engine/core/regular_file.h"

#include <cmath>
#include <cstdio>
#include <vector>

namespace fs = std::filesystem;
using nlohmann::json;

namespace specula {

namespace {
std::string shortNumber(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

// FNV-1a 64-bit, fed in pieces.
struct Fnv1a64 {
    std::uint64_t h = 0xcbf29ce484222325ull;
    void add(const unsigned char* p, std::size_t n) {
        for (std::size_t i = 0; i < n; ++i) {
            h ^= p[i];
            h *= 0x100000001b3ull;
        }
    }
    std::string text() const {
        char hex[32];
        std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
        return std::string("fnv1a64:") + hex;
    }
};
} // namespace

std::string fileChecksum(const std::string& path, std::uint64_t maxBytes) {
    RegularFile file(path, maxBytes);
    Fnv1a64 h;
    std::vector<unsigned char> buf(1 << 16);
    while (const std::size_t got = file.read(buf.data(), buf.size()))
        h.add(buf.data(), got);
    return h.text();
}

std::string bytesChecksum(const void* data, std::size_t size) {
    Fnv1a64 h;
    h.add(static_cast<const unsigned char*>(data), size);
    return h.text();
}

json vec3Json(glm::vec3 v) {
    return json::array({v.x, v.y, v.z});
}

json toJson(const ProbeInputs& inputs) {
    return {{"geometry", inputs.geometry}, {"options", inputs.options}, {"sky", inputs.sky}};
}

ProbeInputs probeInputsFromJson(const json& j, const std::string& file, const std::string& field) {
    if (!j.is_object()) throw Error(file, field, "expected an object");
    const auto member = [&](const char* key) {
        const auto it = j.find(key);
        if (it == j.end() || !it->is_string())
            throw Error(file, field + "." + key, "expected a string");
        return it->get<std::string>();
    };
    return {member("geometry"), member("options"), member("sky")};
}

json probeManifestHeader(std::string_view flavour, const std::string& sourceScene,
                         const ProbeInputs& inputs, bool newest) {
    json header{{"format", formatJson(kProbeFormat, newest)},
                {"flavour", std::string(flavour)},
                {"source", sourceScene}};
    if (inputs.recorded()) header["inputs"] = toJson(inputs);
    return header;
}

ProbeInputs manifestProbeInputs(const json& manifest, const std::string& file) {
    const auto it = manifest.find("inputs");
    return it == manifest.end() ? ProbeInputs{} : probeInputsFromJson(*it, file, "inputs");
}

std::string readManifestText(const std::string& path) {
    return readRegularFile(path, kMaxManifestBytes);
}

std::string manifestSeal(const json& manifest) {
    json unsealed = manifest;
    unsealed.erase("seal");
    const std::string text = unsealed.dump();
    return bytesChecksum(text.data(), text.size());
}

void checkManifestSeal(const ProbeManifest& m) {
    const auto seal = m.json.find("seal");
    if (seal == m.json.end()) return;
    if (!seal->is_string() || *seal != manifestSeal(m.json))
        throw Error(m.path, "seal",
                    "the manifest's fields were edited since Specula wrote it (they no longer "
                    "match its seal): re-cook the probe, or delete \"seal\" to load the edited "
                    "fields as they are");
}

ParsedManifest ParsedManifest::load(const std::string& path) {
    return parse(readManifestText(path), path);
}

ParsedManifest ParsedManifest::parse(const std::string& text, const std::string& path) {
    return ParsedManifest{path, parseManifestJson(text, path)};
}

json parseManifestJson(const std::string& text, const std::string& file) {
    // nlohmann's own messages ("[json.exception.out_of_range.406] number overflow ...") name
    // neither the file nor the field; the parser callback remembers the last key it saw.
    std::string lastKey;
    const json::parser_callback_t remember = [&](int, json::parse_event_t event, json& parsed) {
        if (event == json::parse_event_t::key) lastKey = parsed.get<std::string>();
        return true;
    };
    try {
        return json::parse(text, remember);
    } catch (const json::out_of_range&) {
        throw Error(file, lastKey, "number out of range (beyond what a double can hold)");
    } catch (const json::exception& e) {
        const std::string where = lastKey.empty() ? "" : " (after key \"" + lastKey + "\")";
        throw Error(file, "", std::string("not valid JSON") + where + ": " + e.what());
    }
}

const json& ManifestFields::member(const json& obj, const std::string& key,
                                   const std::string& path) const {
    if (!obj.is_object() || !obj.contains(key))
        throw Error(file, path + key, "missing (expected a value here)");
    return obj.at(key);
}

double ManifestFields::number(const json& obj, const std::string& key, const std::string& path,
                              double lo, double hi, bool nullIsInf) const {
    const json& v = member(obj, key, path);
    if (nullIsInf && v.is_null()) return HUGE_VAL;
    if (!v.is_number()) throw Error(file, path + key, "expected a number");
    const double d = v.get<double>();
    if (!std::isfinite(d) || d < lo || d > hi)
        throw Error(file, path + key,
                    "expected a number in [" + shortNumber(lo) + ", " + shortNumber(hi) +
                        "], got " + v.dump());
    return d;
}

int ManifestFields::integer(const json& obj, const std::string& key, const std::string& path,
                            int lo, int hi) const {
    const double d = number(obj, key, path, lo, hi);
    if (d != std::floor(d))
        throw Error(file, path + key, "expected an integer, got " + obj.at(key).dump());
    return int(d);
}

std::string ManifestFields::string(const json& obj, const std::string& key,
                                   const std::string& path) const {
    const json& v = member(obj, key, path);
    if (!v.is_string()) throw Error(file, path + key, "expected a string");
    return v.get<std::string>();
}

glm::vec3 ManifestFields::vec3(const json& obj, const std::string& key, const std::string& path,
                               float bound) const {
    const json& v = member(obj, key, path);
    if (!v.is_array() || v.size() != 3)
        throw Error(file, path + key, "expected an array of 3 numbers");
    glm::vec3 out;
    for (int i = 0; i < 3; ++i) {
        const double d = v[std::size_t(i)].is_number() ? v[std::size_t(i)].get<double>() : NAN;
        if (!(std::fabs(d) <= double(bound)))
            throw Error(file, path + key,
                        "expected 3 numbers in [-" + shortNumber(bound) + ", " +
                            shortNumber(bound) + "], got " + v.dump());
        out[i] = float(d);
    }
    return out;
}

std::string ManifestFields::fileInFolder(const json& obj, const std::string& path,
                                         const fs::path& dir) const {
    const std::string name = string(obj, "file", path);
    if (name.empty() || fs::path(name).is_absolute() || name.find("..") != std::string::npos ||
        name.find('/') != std::string::npos)
        throw Error(file, path + "file", "expected a plain file name inside the probe folder");
    return (dir / name).string();
}

ManifestFields::CheckedFile ManifestFields::checkedFile(const json& obj, const std::string& path,
                                                        const fs::path& dir,
                                                        std::uint64_t maxBytes) const {
    CheckedFile f;
    f.path = fileInFolder(obj, path, dir);
    f.name = string(obj, "file", path);
    f.checksum =
        checksum(obj, path, namedFile(path, [&] { return fileChecksum(f.path, maxBytes); }));
    return f;
}

std::string ManifestFields::checksum(const json& obj, const std::string& path,
                                     const std::string& actual) const {
    const std::string stored = string(obj, "checksum", path);
    if (stored != actual)
        throw Error(file, path + "checksum",
                    "mismatch for " + string(obj, "file", path) + ": manifest says " + stored +
                        ", file has " + actual);
    return stored;
}

void ManifestFields::rethrowNamed(const std::string& field, const std::exception& e) const {
    throw Error(file, field, e.what());
}

std::string ManifestFields::probeFlavour(const json& m) const {
    readAssetFormat(m, kProbeFormat, file);
    return string(m, "flavour", "");
}

FormatVersion ManifestFields::expectFlavour(const json& m, std::string_view flavour) const {
    const FormatVersion version = readAssetFormat(m, kProbeFormat, file);
    if (const std::string f = string(m, "flavour", ""); f != flavour)
        throw Error(file, "flavour",
                    "expected \"" + std::string(flavour) + "\", got \"" + f + "\"");
    warnAboutNewerMinor(m, kProbeFormat, version, "probe-" + std::string(flavour), file);
    return version;
}

} // namespace specula
