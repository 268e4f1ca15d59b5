#include "engine/core/regular_file.h"

#include "engine/core/error.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace specula {

namespace {

std::string openFailure(int err) {
    switch (err) {
    case ENOENT:
        return "no such file";
    case ELOOP:
        return "too many levels of symbolic links (a symlink loop?)";
    case ENOTDIR:
        return "a component of the path is not a folder";
    case EACCES:
        return "permission denied";
    default:
        return std::strerror(err);
    }
}

std::string kindOf(mode_t mode) {
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a plain file";
}

// Throws unless `st` describes a regular file of at most maxBytes.
void requireRegular(const std::string& path, const struct stat& st, std::uint64_t maxBytes) {
    if (!S_ISREG(st.st_mode))
        throw Error(path, "",
                    "cannot read file: it is " + kindOf(st.st_mode) + ", expected a regular file");
    if (std::uint64_t(st.st_size) > maxBytes)
        throw Error(path, "",
                    "cannot read file: " + std::to_string(st.st_size) + " bytes is more than the " +
                        std::to_string(maxBytes) + "-byte limit for this file");
}

} // namespace

std::uint64_t regularFileSize(const std::string& path, std::uint64_t maxBytes) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0)
        throw Error(path, "", "cannot read file: " + openFailure(errno));
    requireRegular(path, st, maxBytes);
    return std::uint64_t(st.st_size);
}

RegularFile::RegularFile(std::string path, std::uint64_t maxBytes) : path_(std::move(path)) {
    (void)regularFileSize(path_, maxBytes); // a device is refused before it is ever opened
    fd_ = ::open(path_.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd_ < 0) throw Error(path_, "", "cannot read file: " + openFailure(errno));
    struct stat st {};
    if (::fstat(fd_, &st) != 0) {
        const int err = errno;
        ::close(fd_);
        throw Error(path_, "", "cannot read file: " + openFailure(err));
    }
    try {
        requireRegular(path_, st, maxBytes); // the path may have been swapped since the stat
    } catch (...) {
        ::close(fd_);
        throw;
    }
    size_ = std::uint64_t(st.st_size);
}

RegularFile::~RegularFile() {
    if (fd_ >= 0) ::close(fd_);
}

std::size_t RegularFile::read(void* buffer, std::size_t n) {
    const std::uint64_t left = size_ - offset_;
    if (n > left) n = std::size_t(left);
    while (n > 0) {
        const ssize_t got = ::read(fd_, buffer, n);
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) throw Error(path_, "", std::string("read failed: ") + std::strerror(errno));
        offset_ += std::uint64_t(got);
        return std::size_t(got);
    }
    return 0;
}

void RegularFile::readAll(void* buffer) {
    auto* out = static_cast<unsigned char*>(buffer);
    const std::uint64_t start = offset_;
    while (offset_ < size_) {
        const std::size_t got = read(out + (offset_ - start), std::size_t(size_ - offset_));
        if (got == 0)
            throw Error(path_, "",
                        "read failed: the file shrank while being read (" +
                            std::to_string(offset_) + " of " + std::to_string(size_) + " bytes)");
    }
}

} // namespace specula
