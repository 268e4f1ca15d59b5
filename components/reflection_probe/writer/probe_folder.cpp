#include "probe_folder.h"

#include "components/reflection_probe/asset_format.h"
#include "components/reflection_probe/manifest_fields.h"
#include "components/reflection_probe/writer/temporary_owner.h"

#include "engine/core/error.h"
#include "engine/core/file_write.h"
#include "engine/core/regular_file.h"
#include "engine/image/ktx2.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <set>
#include <thread>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using nlohmann::json;

namespace specula {

namespace {

// Set from a signal handler: must be a lock-free atomic, constant-initialised.
std::atomic<bool> gCancel{false};
static_assert(std::atomic<bool>::is_always_lock_free);

// DIR as an absolute path without a trailing separator: "p/" must give p.tmp-PID beside p,
// not p/.tmp-PID inside it.
fs::path folderPath(const std::string& dir) {
    fs::path p = fs::absolute(dir).lexically_normal();
    if (!p.has_filename() && p.has_parent_path() && p != p.root_path()) p = p.parent_path();
    return p;
}

fs::path siblingName(const fs::path& target, const char* kind, long long pid) {
    return target.string() + kind + std::to_string(pid);
}

bool isInside(const fs::path& folder, const fs::path& file) {
    const auto [f, x] = std::mismatch(folder.begin(), folder.end(), file.begin(), file.end());
    return f == folder.end();
}

bool holdsScene(const fs::path& target, const std::string& sourceScene) {
    std::error_code ec;
    if (sourceScene.empty() || !fs::exists(sourceScene, ec)) return false;
    const fs::path scene = fs::weakly_canonical(fs::absolute(sourceScene), ec);
    const fs::path folder = fs::weakly_canonical(target, ec);
    return !ec && isInside(folder, scene);
}

// Every string under a "file" key, at any depth (layers, sky, slabs): what Specula wrote.
// Depth-bounded so that a hostile manifest cannot exhaust the stack; anything deeper simply
// lists nothing, which only makes more files foreign.
// Every listed file with the checksum beside it ("" when it states none).
void collectListedFiles(const json& j, std::map<std::string, std::string>& files, int depth = 0) {
    if (depth > 16) return;
    if (j.is_object()) {
        for (const auto& [key, value] : j.items()) {
            if (key == "file" && value.is_string()) {
                const auto sum = j.find("checksum");
                files[value.get<std::string>()] =
                    sum != j.end() && sum->is_string() ? sum->get<std::string>() : "";
            } else {
                collectListedFiles(value, files, depth + 1);
            }
        }
    } else if (j.is_array()) {
        for (const json& v : j)
            collectListedFiles(v, files, depth + 1);
    }
}

// The JSON in a regular file, or null when it cannot be read or parsed (the caller decides
// what a non-manifest means).
json parseJsonOrNull(const fs::path& file, std::uint64_t maxBytes) {
    try {
        return json::parse(readRegularFile(file.string(), maxBytes), nullptr, false);
    } catch (const Error&) {
        return json();
    }
}

// Whether `file` is named and begins like a KTX 2.0 texture (its 12-byte identifier).
bool isKtx2Texture(const fs::path& file) {
    if (file.extension() != ".ktx2") return false;
    try {
        RegularFile f(file.string(), std::uint64_t(16) << 30);
        unsigned char head[sizeof kKtx2Identifier] = {};
        return f.read(head, sizeof head) == sizeof head &&
               std::memcmp(head, kKtx2Identifier, sizeof head) == 0;
    } catch (const Error&) {
        return false;
    }
}

// The files a Specula manifest lists, with their checksums; throws when manifest.json is not
// one.
std::map<std::string, std::string> probeFolderFiles(const fs::path& manifest,
                                                    const std::string& dir) {
    std::error_code ec;
    const auto st = fs::symlink_status(manifest, ec);
    if (!fs::exists(st))
        throw Error(dir, "",
                    "is a folder without manifest.json (not a cooked probe); refusing to "
                    "replace it");
    constexpr std::uintmax_t kMaxManifestBytes = 64u << 20;
    const json j = fs::is_regular_file(st) ? parseJsonOrNull(manifest, kMaxManifestBytes) : json();
    if (assetFormatName(j) != std::string(kProbeFormat.name))
        throw Error(dir, "manifest.json",
                    "is not a Specula probe manifest (no \"format\" named \"specula-probe\"); "
                    "refusing to replace a folder Specula did not write");
    std::map<std::string, std::string> files;
    collectListedFiles(j, files);
    return files;
}

// Test hook, documented in tests/tools/output_safety_test.cpp: with
// SPECULA_TEST_PAUSE_BEFORE_COMMIT=S the finished temporary folder (manifest included) waits
// up to S seconds before the commit check, so a test can signal at a moment that is surely
// before the rename. A cancel request ends the wait at once. Unset: no cost, no effect.
void pauseBeforeCommitForTests() {
    const char* s = std::getenv("SPECULA_TEST_PAUSE_BEFORE_COMMIT");
    if (!s) return;
    const double seconds = std::clamp(std::atof(s), 0.0, 60.0);
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (!cancelRequested() && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
}

[[noreturn]] void throwMoveFailed(const std::string& dir, int error) {
    throw Error(dir, "",
                std::string("cannot move the finished probe into place: ") + std::strerror(error));
}

// The commit point: the finished folder takes DIR's place in a single rename. Where DIR
// exists the two are exchanged atomically (renameat2), so DIR never goes missing; the
// previous probe then sits at the temporary name and is removed with it.
void commit(const fs::path& tmp, const fs::path& target, const std::string& dir,
            const std::string& sourceScene) {
    checkProbeFolderReplaceable(dir, sourceScene); // files a user added during the bake
    throwIfCancelled(dir);
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(target, ec))) {
        if (std::rename(tmp.c_str(), target.c_str()) != 0) throwMoveFailed(dir, errno);
        return;
    }
    if (::renameat2(AT_FDCWD, tmp.c_str(), AT_FDCWD, target.c_str(), RENAME_EXCHANGE) == 0) {
        // The previous probe now sits at the temporary name: owned again before it is removed,
        // so a kill during the removal leaves a folder the next run may clear.
        try {
            writeTemporaryOwner(tmp);
        } catch (const Error&) {
        }
        fs::remove_all(tmp, ec);
        return;
    }
    if (errno != EINVAL && errno != ENOSYS) throwMoveFailed(dir, errno);
    // A filesystem without exchange: two renames, the previous probe at DIR.old-PID between
    // them (a crash there is repaired by removeStaleProbeTemporaries).
    const fs::path old = siblingName(target, ".old-", ::getpid());
    if (std::rename(target.c_str(), old.c_str()) != 0) throwMoveFailed(dir, errno);
    try {
        writeTemporaryOwner(old); // removed with it, or before it is restored
    } catch (const Error&) {
        std::rename(old.c_str(), target.c_str());
        throw;
    }
    if (std::rename(tmp.c_str(), target.c_str()) != 0) {
        const int error = errno;
        std::rename(old.c_str(), target.c_str());
        throwMoveFailed(dir, error);
    }
    fs::remove_all(old, ec);
}

} // namespace

void requestCancel() noexcept {
    gCancel.store(true, std::memory_order_relaxed);
}

void clearCancelRequest() noexcept {
    gCancel.store(false, std::memory_order_relaxed);
}

bool cancelRequested() noexcept {
    return gCancel.load(std::memory_order_relaxed);
}

void throwIfCancelled(const std::string& dir) {
    if (cancelRequested())
        throw Cancelled(dir, "", "interrupted by a signal; the folder was left as it was");
}

void checkProbeFolderReplaceable(const std::string& dir, const std::string& sourceScene) {
    const fs::path target = folderPath(dir);
    std::error_code ec;
    const auto st = fs::status(target, ec);
    if (!fs::exists(st)) return;
    if (!fs::is_directory(st))
        throw Error(dir, "", "exists and is not a folder; refusing to replace it");
    if (holdsScene(target, sourceScene))
        throw Error(dir, "",
                    "holds the input scene " + sourceScene +
                        "; refusing to replace it (choose another folder)");
    if (fs::is_empty(target, ec) && !ec) return;
    const std::map<std::string, std::string> listed =
        probeFolderFiles(target / "manifest.json", dir);
    std::vector<fs::directory_entry> entries(fs::directory_iterator(target),
                                             fs::directory_iterator{});
    std::sort(entries.begin(), entries.end());
    for (const fs::directory_entry& e : entries) {
        const std::string name = e.path().filename().string();
        if (name == "manifest.json") continue;
        const auto it = listed.find(name);
        if (it == listed.end() || !e.is_regular_file() || e.is_symlink())
            throw Error(dir, name,
                        "is not one of the files its manifest.json lists (Specula did not "
                        "write it); refusing to replace the folder");
        // A manifest names a file by its bytes too: a manifest forged to list a user's file
        // does not make it Specula's to delete. A texture of ours damaged since (the level's
        // re-bake repairs those) still is one.
        if (!it->second.empty() && fileChecksum(e.path().string()) == it->second) continue;
        if (!isKtx2Texture(e.path()))
            throw Error(dir, name,
                        "is listed by its manifest.json, but its bytes are neither the ones the "
                        "manifest records nor a KTX2 texture (not written by Specula); "
                        "refusing to replace the folder");
    }
}

void removeStaleProbeTemporaries(const std::string& dir, std::ostream& log) {
    const fs::path target = folderPath(dir);
    const std::string base = target.filename().string();
    std::error_code ec;
    if (base.empty() || !fs::is_directory(target.parent_path(), ec)) return;
    struct Stale {
        fs::path path;
        long long pid;
        bool old;
    };
    std::vector<Stale> stale;
    std::vector<fs::directory_entry> entries(fs::directory_iterator(target.parent_path(), ec),
                                             fs::directory_iterator{});
    std::sort(entries.begin(), entries.end());
    for (const auto& e : entries) {
        const std::string name = e.path().filename().string();
        for (const char* kind : {".tmp-", ".old-"}) {
            const std::string prefix = base + kind;
            if (!name.starts_with(prefix) || name.size() - prefix.size() > 9) continue;
            long long pid = 0;
            const char* first = name.data() + prefix.size();
            const char* last = name.data() + name.size();
            const auto [end, err] = std::from_chars(first, last, pid);
            if (err != std::errc() || end != last || first == last || pid <= 0) continue;
            if (!e.is_directory(ec) || e.is_symlink(ec)) continue; // only what a bake makes
            if (pid == ::getpid()) continue;                       // this run's own
            if (const std::string why = whyTemporaryIsNotStale(e.path(), pid); !why.empty()) {
                log << "left " << e.path().string() << " as it is: " << why << "\n";
                continue;
            }
            stale.push_back({e.path(), pid, kind[1] == 'o'});
        }
    }
    for (const Stale& s : stale) {
        const std::string why =
            " (left by process " + std::to_string(s.pid) + " on this host, which no longer runs)";
        if (s.old && !fs::exists(fs::symlink_status(target, ec))) {
            fs::remove(s.path / kTemporaryOwnerFile, ec);
            fs::rename(s.path, target, ec);
            if (ec) throw Error(s.path.string(), "", "cannot restore it: " + ec.message());
            log << "restored " << target.string() << " from " << s.path.string() << why << "\n";
        } else {
            fs::remove_all(s.path, ec);
            if (ec) throw Error(s.path.string(), "", "cannot remove it: " + ec.message());
            log << "removed stale " << s.path.string() << why << "\n";
        }
    }
}

namespace {

// A file written beside and renamed (file_write.h) that its writer left, killed: removed when
// its name says this host's process, which no longer runs, wrote it. One named for no host
// (written before names carried it) is left, as is a live or another host's writer's.
void removeStaleTemporaryFile(const fs::path& file, const std::string& folder, std::ostream& log) {
    const std::optional<TemporaryFileName> t = parseTemporaryFileName(file.filename().string());
    if (!t) {
        log << "left " << file.string()
            << " as it is: a temporary file, which names no host (delete it by hand once no "
               "specula-cook writes "
            << folder << ")\n";
        return;
    }
    if (const std::string why = whyOwnerMayRun(t->host, t->pid); !why.empty()) {
        log << "left " << file.string() << " as it is: " << why << "\n";
        return;
    }
    std::error_code ec;
    fs::remove(file, ec);
    if (ec) throw Error(file.string(), "", "cannot remove it: " + ec.message());
    log << "removed stale " << file.string() << " (left by process " << t->pid
        << " on this host, which no longer runs)\n";
}

} // namespace

void removeStaleTemporariesIn(const std::string& folder, std::ostream& log) {
    std::error_code ec;
    std::set<std::string> outputs; // X of every X.tmp-PID and X.old-PID folder
    for (const auto& e : fs::directory_iterator(folder, ec)) {
        const std::string name = e.path().filename().string();
        for (const char* kind : {".tmp-", ".old-"}) {
            const std::size_t at = name.rfind(kind);
            if (at == std::string::npos || at == 0) continue;
            if (e.is_directory(ec) && !e.is_symlink(ec))
                outputs.insert(name.substr(0, at));
            else if (kind[1] == 't' && e.is_regular_file(ec) && !e.is_symlink(ec))
                removeStaleTemporaryFile(e.path(), folder, log);
        }
    }
    for (const std::string& x : outputs)
        removeStaleProbeTemporaries((fs::path(folder) / x).string(), log);
}

void writeProbeFolder(const std::string& dir, const std::string& sourceScene,
                      const std::function<json(const fs::path& tmp)>& fill) {
    checkProbeFolderReplaceable(dir, sourceScene);
    throwIfCancelled(dir);
    const fs::path target = folderPath(dir);
    const fs::path tmp = siblingName(target, ".tmp-", ::getpid());
    const fs::path createdParent = outermostMissingFolder(target.parent_path());
    std::error_code ec;
    fs::remove_all(tmp, ec);
    fs::create_directories(tmp);
    try {
        writeTemporaryOwner(tmp); // first: whoever finds it left knows whose it was
        json manifest = fill(tmp);
        manifest["seal"] = manifestSeal(manifest);
        throwIfCancelled(dir);
        writeFileAtomically((tmp / "manifest.json").string(), manifest.dump(2) + "\n");
        pauseBeforeCommitForTests();
        fs::remove(tmp / kTemporaryOwnerFile); // the probe folder holds only what it lists
        commit(tmp, target, dir, sourceScene);
    } catch (...) {
        fs::remove_all(tmp, ec);
        removeEmptyFoldersUpTo(target.parent_path(), createdParent);
        throw;
    }
}

} // namespace specula
