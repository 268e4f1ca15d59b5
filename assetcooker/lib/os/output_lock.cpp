#include "assetcooker/lib/os/output_lock.h"

#include "components/reflection_probe/writer/temporary_owner.h"
#include "engine/core/error.h"
#include "engine/core/file_write.h"
#include "engine/core/host_name.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace specula {

namespace fs = std::filesystem;

namespace {

constexpr std::size_t kMaxLockBytes = 64 * 1024;

std::vector<std::string> holderLines(const std::string& path) {
    std::vector<std::string> lines;
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) return lines;
    std::string text(kMaxLockBytes, '\0');
    const ssize_t n = ::read(fd, text.data(), text.size());
    ::close(fd);
    text.resize(n > 0 ? std::size_t(n) : 0);
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (!line.empty()) lines.push_back(line);
    return lines;
}

// "bake-shard host H pid P" -> "bake-shard (host H, pid P)"; "" for the line of a shared
// holder that ended (its host is this one and its process no longer runs: a shared holder
// that is not the last leaves its line behind).
std::string describeHolder(const std::string& line) {
    const std::size_t host = line.find(" host ");
    const std::size_t pid = line.rfind(" pid ");
    if (host == std::string::npos || pid == std::string::npos || pid < host) return line;
    const std::string hostText = line.substr(host + 6, pid - host - 6);
    const std::string pidText = line.substr(pid + 5);
    const long long number = std::atoll(pidText.c_str());
    if (hostText == hostName() && number > 0 && !processRunsHere(number)) return "";
    return line.substr(0, host) + " (host " + hostText + ", pid " + pidText + ")";
}

bool sameFile(int fd, const std::string& path) {
    struct stat a {
    }, b{};
    return ::fstat(fd, &a) == 0 && ::stat(path.c_str(), &b) == 0 && a.st_dev == b.st_dev &&
           a.st_ino == b.st_ino;
}

[[noreturn]] void throwSystem(const std::string& path, const char* what, int error) {
    throw Error(path, "", std::string(what) + ": " + std::strerror(error));
}

} // namespace

std::string outputLockPath(const std::string& out) {
    fs::path p = fs::absolute(out).lexically_normal();
    if (!p.has_filename() && p.has_parent_path() && p != p.root_path()) p = p.parent_path();
    return p.string() + ".lock";
}

OutputLock::OutputLock(const std::string& out, const std::string& command, FileLockMode mode)
    : path_(outputLockPath(out)),
      holder_("host " + hostName() + " pid " + std::to_string(::getpid())), mode_(mode) {
    const fs::path parent = fs::path(path_).parent_path();
    createdParent_ = outermostMissingFolder(parent);
    std::error_code ec;
    fs::create_directories(parent, ec);
    if (ec) throw Error(path_, "", "cannot create its folder: " + ec.message());
    // The last holder removes the file: a lock taken on a file no longer at the path is
    // nobody's, so take the one that is there now.
    for (;;) {
        const int fd = ::open(path_.c_str(), O_RDWR | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
        if (fd < 0) throwSystem(path_, "cannot open the output lock", errno);
        if (!tryLockFile(fd, mode)) {
            const int error = errno;
            ::close(fd);
            if (error != EWOULDBLOCK) throwSystem(path_, "cannot lock the output", error);
            const std::vector<std::string> lines = holderLines(path_);
            const char* behalf = std::getenv(kLockHolderVariable);
            for (const std::string& line : lines)
                if (behalf && *behalf && line.ends_with(std::string(" ") + behalf))
                    return; // a job of the holder's: it runs under the holder's lock
            std::string holders;
            for (const std::string& line : lines)
                if (const std::string h = describeHolder(line); !h.empty())
                    holders += (holders.empty() ? "" : ", ") + h;
            if (holders.empty()) holders = "one that has not yet named itself";
            throw Error(out, "",
                        "is being written by another specula-cook: " + holders + " (lock file " +
                            path_ + "); one writer at a time: wait for it to end, or stop it");
        }
        if (sameFile(fd, path_)) {
            fd_ = fd;
            break;
        }
        ::close(fd);
    }
    // The exclusive holder is the only one named; each shared holder adds its line.
    if (mode_ == FileLockMode::Exclusive && ::ftruncate(fd_, 0) != 0) {
        const int error = errno;
        ::close(fd_);
        throwSystem(path_, "cannot write the output lock", error);
    }
    const std::string line = command + " " + holder_ + "\n";
    if (::write(fd_, line.data(), line.size()) != ssize_t(line.size())) {
        const int error = errno;
        ::close(fd_);
        throwSystem(path_, "cannot write the output lock", error);
    }
}

OutputLock::~OutputLock() {
    if (fd_ < 0) return;
    // The last holder removes the file (a shared holder is the last when it can take the
    // lock exclusively), before it lets go of the lock.
    if (mode_ == FileLockMode::Exclusive || tryLockFile(fd_, FileLockMode::Exclusive))
        ::unlink(path_.c_str());
    ::close(fd_);
    removeEmptyFoldersUpTo(fs::path(path_).parent_path(), createdParent_);
}

} // namespace specula
