#pragma once
// What every cooked-probe manifest reader shares (distance and light field): reading the
// manifest as a bounded regular file, parsing it so that even a number JSON cannot hold
// names its field, and typed, range-checked field access that names the file and the JSON
// path on every failure.
#include "components/reflection_probe/asset_format.h"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

namespace specula {

// A manifest is a few kB; an effect plan for a level of tens of thousands of nodes a few
// MB. Anything larger is not a manifest.
inline constexpr std::uint64_t kMaxManifestBytes = 64ull << 20;

// Bound on every world-space coordinate a manifest holds (probe centres, light-field cells).
// A float has a 24-bit mantissa: at 1e7 m neighbouring floats are 1 m apart, so a centre
// beyond that cannot place a probe to the metre, and a centre such as 1e308 is not a
// float at all. No real level is 10,000 km across.
inline constexpr float kMaxCoordinate = 1e7f;

// FNV-1a 64-bit of a file's bytes as "fnv1a64:<16 hex digits>", the checksum a manifest
// stores for every file it names. Only a regular file of at most maxBytes is read (never a
// FIFO, device or directory). Throws Error naming the file.
std::string fileChecksum(const std::string& path, std::uint64_t maxBytes = 16ull << 30);
// The same checksum of bytes in memory.
std::string bytesChecksum(const void* data, std::size_t size);

// What a probe was baked from, each as a checksum (the cooker computes them): a changed one
// says why a level's probe is re-baked, or that a probe is loaded against another scene.
// Empty (geometry "") where nothing was recorded: a probe of an older cooker, or written by
// hand.
struct ProbeInputs {
    std::string geometry; // the meshes and reflectors within the probe's reach, in world space
    std::string options;  // the flavour, its settings and the probe's volumes
    std::string sky;      // the sky image's bytes ("none" without one)

    bool operator==(const ProbeInputs&) const = default;
    bool recorded() const { return !geometry.empty(); }
};
// {"geometry", "options", "sky"}, the "inputs" member of a manifest or a level's probe.
nlohmann::json toJson(const ProbeInputs& inputs);
// `j` as ProbeInputs; throws Error(file, field + member) unless it is an object of three
// strings.
ProbeInputs probeInputsFromJson(const nlohmann::json& j, const std::string& file,
                                const std::string& field);

// A vec3 as the JSON array a manifest stores.
nlohmann::json vec3Json(glm::vec3 v);

// The members every cooked manifest opens with: "format" (kProbeFormat, asset_format.h: its
// newest version when the asset uses what only that holds, `newest`, else its plainVersion),
// "flavour", "source" (the scene it was baked from) and, when recorded, "inputs".
nlohmann::json probeManifestHeader(std::string_view flavour, const std::string& sourceScene,
                                   const ProbeInputs& inputs, bool newest = false);
// A manifest's optional "inputs" (empty when absent); Error naming "inputs.*" when malformed.
ProbeInputs manifestProbeInputs(const nlohmann::json& manifest, const std::string& file);

// The manifest text at `path`, read as a regular file of at most kMaxManifestBytes.
std::string readManifestText(const std::string& path);

// Parses manifest text. A syntax error or a number beyond double range ("d_inf": 1e999)
// throws Error naming `file` and the last key read before the failure.
nlohmann::json parseManifestJson(const std::string& text, const std::string& file);

// A cooked manifest, read and parsed once per load: its path (for errors and the files it
// names) and its JSON. A view: ParsedManifest owns.
struct ProbeManifest {
    const std::string& path;
    const nlohmann::json& json;
};

// The manifest's seal: the checksum of its JSON without "seal" (nlohmann's dump, keys sorted,
// so a parsed manifest dumps to the same text). Written last by writeProbeFolder; a manifest
// whose fields were edited since no longer matches it.
std::string manifestSeal(const nlohmann::json& manifest);
// Throws Error(file, "seal") when the manifest carries a seal its fields do not match. The
// readers call it after every field is validated, so a bad field is named as such. A
// manifest without "seal" (written by hand, or unsealed on purpose) passes.
void checkManifestSeal(const ProbeManifest& m);

// A manifest read from disk (load) or parsed from text in memory (parse), owning its JSON.
// Throws Error naming the file (and, for a syntax error, the last key read).
struct ParsedManifest {
    std::string path;
    nlohmann::json json;

    static ParsedManifest load(const std::string& path);
    static ParsedManifest parse(const std::string& text, const std::string& path);
    ProbeManifest view() const { return {path, json}; }
};

// Typed access to a manifest's JSON; every failure throws Error(file, path + key, ...).
struct ManifestFields {
    const std::string& file;

    const nlohmann::json& member(const nlohmann::json& obj, const std::string& key,
                                 const std::string& path) const;
    // A finite number in [lo, hi]; with nullIsInf, JSON null reads as +infinity (JSON has no
    // infinity, so writers store an infinite depth as null).
    double number(const nlohmann::json& obj, const std::string& key, const std::string& path,
                  double lo, double hi, bool nullIsInf = false) const;
    // A number in [lo, hi] with no fractional part (32.5 is refused, not truncated).
    int integer(const nlohmann::json& obj, const std::string& key, const std::string& path, int lo,
                int hi) const;
    std::string string(const nlohmann::json& obj, const std::string& key,
                       const std::string& path) const;
    // Three numbers, each within [-bound, bound] (and so a float).
    glm::vec3 vec3(const nlohmann::json& obj, const std::string& key, const std::string& path,
                   float bound) const;
    // The file named at path + "file": a plain name inside `dir`. Returns dir / name.
    std::string fileInFolder(const nlohmann::json& obj, const std::string& path,
                             const std::filesystem::path& dir) const;
    // The file named at path + "file" (fileInFolder) with its bytes (at most maxBytes, a
    // regular file) checked against path + "checksum"; a file that cannot be read is an
    // error naming path + "file" (namedFile).
    struct CheckedFile {
        std::string path;     // dir / name
        std::string name;     // as the manifest names it
        std::string checksum; // as the manifest stores it (and the file has)
    };
    CheckedFile checkedFile(const nlohmann::json& obj, const std::string& path,
                            const std::filesystem::path& dir, std::uint64_t maxBytes) const;
    // Compares the checksum stored at path + "checksum" with `actual`; returns the stored one.
    std::string checksum(const nlohmann::json& obj, const std::string& path,
                         const std::string& actual) const;
    // The "flavour" of a Specula probe manifest of a format this runtime reads
    // (readAssetFormat, asset_format.h); another format or major is refused naming the field.
    std::string probeFlavour(const nlohmann::json& manifest) const;
    // probeFlavour, which must be `flavour` (every flavour's reader opens with it, so all
    // refuse a foreign manifest with the same message). A newer minor's members this runtime
    // does not know are listed once in a warning (warnAboutNewerMinor). Returns the version.
    FormatVersion expectFlavour(const nlohmann::json& manifest, std::string_view flavour) const;
    // Runs `read` on a file the manifest names; an Error it throws (the file is missing, a
    // FIFO, a directory, a symlink loop...) is re-thrown naming the manifest and the field
    // as well.
    template <typename Read> auto namedFile(const std::string& path, Read read) const {
        try {
            return read();
        } catch (const std::exception& e) {
            rethrowNamed(path + "file", e);
        }
    }

private:
    [[noreturn]] void rethrowNamed(const std::string& field, const std::exception& e) const;
};

} // namespace specula
