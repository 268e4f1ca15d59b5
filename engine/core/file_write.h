#pragma once
// Writing a file so that nobody ever reads a partial one: the bytes go to PATH.tmp-PID
// beside it, every write() and the close() are checked (a full disk or a file-size limit
// shows up there, not later as a truncated file), and only a complete file is renamed over
// PATH. On failure the temporary file is removed and PATH is left as it was. Header-only so
// that every engine library can use it without linking specula_core.
#include "engine/core/error.h"
#include "engine/core/host_name.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include <fcntl.h>
#include <unistd.h>

namespace specula {

// The temporary name beside `path` that this process writes before the rename:
// PATH.tmp-HOST-PID, so that whoever finds it left (a killed writer) can tell whose it was
// and whether that process still runs (parseTemporaryFileName).
inline std::string temporaryNameFor(const std::string& path) {
    return path + ".tmp-" + hostName() + "-" + std::to_string(::getpid());
}

// A name temporaryNameFor made: the file it stands for, the host and the pid; none otherwise.
struct TemporaryFileName {
    std::string target, host;
    long long pid = 0;
};
inline std::optional<TemporaryFileName> parseTemporaryFileName(const std::string& name) {
    const std::size_t at = name.rfind(".tmp-"), dash = name.rfind('-');
    if (at == std::string::npos || at == 0 || dash <= at + 5 || dash + 1 == name.size())
        return std::nullopt;
    TemporaryFileName t{name.substr(0, at), name.substr(at + 5, dash - at - 5), 0};
    for (std::size_t i = dash + 1; i < name.size(); ++i) {
        if (name[i] < '0' || name[i] > '9' || t.pid > 1'000'000'000) return std::nullopt;
        t.pid = t.pid * 10 + (name[i] - '0');
    }
    if (t.pid <= 0) return std::nullopt;
    return t;
}

// Writes every byte of `bytes` to `fd`, again after EINTR. Returns 0, or the errno of the
// write that failed (EIO for one that wrote nothing); `done` says how many bytes went out.
inline int writeAll(int fd, std::string_view bytes, std::size_t& done) {
    done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return n < 0 ? errno : EIO;
        done += std::size_t(n);
    }
    return 0;
}

// " (D of N bytes written)": what a failed write message adds.
inline std::string bytesWrittenNote(std::size_t done, std::size_t total) {
    return " (" + std::to_string(done) + " of " + std::to_string(total) + " bytes written)";
}

inline void writeFileAtomically(const std::string& path, std::string_view bytes) {
    const std::string tmp = temporaryNameFor(path);
    auto fail = [&](int error, const std::string& context) {
        ::unlink(tmp.c_str());
        throw Error(path, "", std::string("cannot write: ") + std::strerror(error) + context);
    };
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) {
        const int error = errno;
        fail(error, "");
    }
    std::size_t done = 0;
    if (const int error = writeAll(fd, bytes, done)) {
        ::close(fd);
        fail(error, bytesWrittenNote(done, bytes.size()));
    }
    if (::close(fd) != 0) {
        const int error = errno;
        fail(error, " (on close)");
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        const int error = errno;
        fail(error, " (renaming the finished file)");
    }
}

// The outermost folder that std::filesystem::create_directories(folder) would create (empty
// when `folder` exists): what a failed run must remove again, and nothing above it.
inline std::filesystem::path outermostMissingFolder(const std::filesystem::path& folder) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::path p = fs::absolute(folder).lexically_normal(), missing;
    if (!p.has_filename()) p = p.parent_path();
    while (!p.empty() && !fs::exists(fs::symlink_status(p, ec))) {
        missing = p;
        if (p == p.parent_path()) break;
        p = p.parent_path();
    }
    return missing;
}

// Removes `folder` and then its parents up to `outermost` (inclusive) while they are empty.
inline void removeEmptyFoldersUpTo(const std::filesystem::path& folder,
                                   const std::filesystem::path& outermost) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (outermost.empty()) return;
    fs::path p = fs::absolute(folder).lexically_normal();
    if (!p.has_filename()) p = p.parent_path();
    for (; p.string().size() >= outermost.string().size(); p = p.parent_path())
        if (!fs::remove(p, ec) || p == outermost) break; // fs::remove only takes empty folders
}

} // namespace specula
