#pragma once
// The little-endian binary files the cooker writes between machines (a light-field part
// shard, lightfield_rows.h; a PEM trace or sample shard, pem_shard_files.h): the same bytes
// whatever the host, every read checked against the bytes left, so a truncated file is an
// Error naming it and the field, never a read past the end. Header-only: the fuzz replays
// build lightfield_rows.cpp without the cooker library.
#include "engine/core/error.h"
#include "engine/core/regular_file.h"

#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <type_traits>

namespace specula::binary {

// Little-endian, whatever the host.
template <class T> void put(std::string& out, T value) {
    std::uint64_t bits = 0;
    if constexpr (std::is_same_v<T, float>) {
        bits = std::bit_cast<std::uint32_t>(value);
    } else {
        bits = std::uint64_t(value);
    }
    for (std::size_t i = 0; i < sizeof(T); ++i)
        out.push_back(char((bits >> (8 * i)) & 0xff));
}

// Reads the file's fields in order; every read checked against the bytes left.
class Reader {
public:
    Reader(const std::string& file, const std::string& bytes) : file_(file), bytes_(bytes) {}

    template <class T> T get(const std::string& field) {
        need(sizeof(T), field);
        std::uint64_t bits = 0;
        for (std::size_t i = 0; i < sizeof(T); ++i)
            bits |= std::uint64_t(std::uint8_t(bytes_[at_ + i])) << (8 * i);
        at_ += sizeof(T);
        if constexpr (std::is_same_v<T, float>)
            return std::bit_cast<float>(std::uint32_t(bits));
        else
            return T(bits);
    }
    void need(std::size_t count, const std::string& field) const {
        if (count > bytes_.size() - at_)
            throw Error(file_, field,
                        "truncated: needs " + std::to_string(count) + " more bytes, the file has " +
                            std::to_string(bytes_.size() - at_) + " left (" +
                            std::to_string(bytes_.size()) + " bytes in all)");
    }
    const char* here() const { return bytes_.data() + at_; }
    void skip(std::size_t count) { at_ += count; }
    std::size_t left() const { return bytes_.size() - at_; }

private:
    const std::string& file_;
    const std::string& bytes_;
    std::size_t at_ = 0;
};

// Shard files are the cooker's own, but a store on a shared disk is anyone's: a FIFO or a
// device planted there must not hang or flood a reader (regular_file.h). Past any real shard.
inline constexpr std::uint64_t kMaxShardFileBytes = std::uint64_t(64) << 30;

// The whole file; Error naming it when it cannot be read or is no regular file.
inline std::string readAll(const std::string& file) {
    return readRegularFile(file, kMaxShardFileBytes);
}

} // namespace specula::binary
