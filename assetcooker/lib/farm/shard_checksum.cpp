#include "assetcooker/lib/farm/shard_checksum.h"

#include "components/reflection_probe/manifest_fields.h"
#include "engine/core/error.h"
#include "engine/core/file_write.h"

#include <filesystem>
#include <map>

namespace specula {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr const char* kSumFormat = "specula-shard-sum";
constexpr int kSumVersion = 1;

// Every regular file of the shard's output: path relative to a folder shard, or the file
// shard's own name; anything else (a link, a folder holding a link) as "" so that it is
// reported, never followed.
std::map<std::string, std::string> outputFiles(const std::string& output, bool folder) {
    std::map<std::string, std::string> files;
    std::error_code ec;
    if (!folder) {
        if (fs::is_regular_file(fs::symlink_status(output, ec)))
            files[fs::path(output).filename().string()] = output;
        return files;
    }
    for (auto it = fs::recursive_directory_iterator(output, ec);
         it != fs::recursive_directory_iterator(); it.increment(ec)) {
        if (ec) break;
        const std::string name = fs::relative(it->path(), output, ec).string();
        if (it->is_symlink(ec))
            files[name] = "";
        else if (it->is_regular_file(ec))
            files[name] = it->path().string();
    }
    return files;
}

} // namespace

std::string shardSumPath(const std::string& dir, const Shard& s) {
    return (fs::path(shardStore(dir)) / (s.hash + ".sum.json")).string();
}

bool shardSumPresent(const std::string& dir, const Shard& s) {
    std::error_code ec;
    return fs::is_regular_file(shardSumPath(dir, s), ec);
}

void writeShardSum(const std::string& dir, const Shard& s) {
    json files = json::object();
    for (const auto& [name, path] : outputFiles(shardOutputPath(dir, s), s.kind == kProbeShard))
        if (!path.empty()) files[name] = fileChecksum(path);
    const json doc = {{"format", kSumFormat},
                      {"version", kSumVersion},
                      {"shard", s.hash},
                      {"kind", s.kind},
                      {"files", files}};
    writeFileAtomically(shardSumPath(dir, s), doc.dump(2) + "\n");
}

void verifyShard(const std::string& dir, const ShardList& list, int index) {
    const Shard& s = list.shards[std::size_t(index)];
    const std::string output = shardOutputPath(dir, s), sumFile = shardSumPath(dir, s);
    const std::string shard =
        "shard " + std::to_string(index) + " (" + shardLabel(list, index) + ", " + s.hash + ")";
    const std::string remedy = "; delete " + output + " and run specula-cook bake-shard " + dir +
                               " --shard " + std::to_string(index) + " (nothing was merged)";
    auto refuse = [&](const std::string& file, const std::string& why) {
        throw Error(file, "", shard + ": " + why + remedy);
    };
    if (!shardSumPresent(dir, s))
        refuse(sumFile, "missing: the store's copy of the shard has no checksums (baked by an "
                        "older specula-cook, or killed before they were written)");
    json doc;
    try {
        doc = parseManifestJson(readManifestText(sumFile), sumFile);
    } catch (const Error& e) {
        refuse(sumFile, std::string("unreadable (") + e.what() + ")");
    }
    if (!doc.is_object() || doc.value("format", "") != kSumFormat ||
        doc.value("version", 0) != kSumVersion || !doc.contains("files") ||
        !doc["files"].is_object())
        refuse(sumFile, std::string("is not a ") + kSumFormat + " of version " +
                            std::to_string(kSumVersion));
    if (doc.value("shard", "") != s.hash || doc.value("kind", "") != s.kind)
        refuse(sumFile, "records shard " + doc.value("shard", std::string("?")) + " (" +
                            doc.value("kind", std::string("?")) +
                            "), not this one: swapped with another shard's");
    const std::map<std::string, std::string> files = outputFiles(output, s.kind == kProbeShard);
    for (const auto& [name, sum] : doc["files"].items()) {
        const auto it = files.find(name);
        const std::string path =
            s.kind == kProbeShard ? (fs::path(output) / name).string() : output;
        if (it == files.end() || it->second.empty()) refuse(path, "missing from the store");
        if (!sum.is_string() || fileChecksum(it->second) != sum.get<std::string>())
            refuse(path,
                   "altered or truncated: its checksum is not the one recorded in " + sumFile);
    }
    for (const auto& [name, path] : files)
        if (!doc["files"].contains(name))
            refuse(path.empty() ? (fs::path(output) / name).string() : path,
                   "not part of the shard as baked (not in " + sumFile + ")");
}

} // namespace specula
