#pragma once
// Reading user files safely. A FIFO blocks a reader forever, a device such as /dev/zero never
// ends, a directory reads as zero bytes and a symlink loop surfaces as a raw filesystem error;
// every reader of a user's file (manifests, checksums, images, glTF buffers) goes through
// here instead, so each of those gets one clear Error naming the file, and no read is
// unbounded.
#include <cstddef>
#include <cstdint>
#include <string>

namespace specula {

// A regular file opened for reading. The path (symlinks followed) is checked before the open
// (so a device is never opened) and the open descriptor again after it (so nothing can be
// swapped in between); the open never blocks, so a FIFO is refused rather than waited on.
// Reads stop at the size seen at open, which must be at most maxBytes.
class RegularFile {
public:
    // Throws Error(path, "", "cannot read file: <why>").
    RegularFile(std::string path, std::uint64_t maxBytes);
    ~RegularFile();
    RegularFile(const RegularFile&) = delete;
    RegularFile& operator=(const RegularFile&) = delete;

    std::uint64_t size() const { return size_; }
    const std::string& path() const { return path_; }
    // Up to n bytes from the current position; 0 once size() bytes have been read.
    std::size_t read(void* buffer, std::size_t n);
    // The rest of the file into `buffer` (which holds size() bytes); throws Error when the
    // file ends early (it shrank while being read).
    void readAll(void* buffer);

private:
    std::string path_;
    int fd_ = -1;
    std::uint64_t size_ = 0, offset_ = 0;
};

// The size of a regular file of at most maxBytes, without reading it; throws Error like
// RegularFile (for readers such as OpenImageIO that open the file themselves).
std::uint64_t regularFileSize(const std::string& path, std::uint64_t maxBytes);

// The whole of a regular file of at most maxBytes, as std::string or a byte vector.
template <typename Bytes = std::string>
Bytes readRegularFile(const std::string& path, std::uint64_t maxBytes) {
    RegularFile file(path, maxBytes);
    Bytes bytes(static_cast<std::size_t>(file.size()), 0);
    file.readAll(bytes.data());
    return bytes;
}

} // namespace specula
