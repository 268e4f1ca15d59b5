#include "assetcooker/lib/os/memory_estimate.h"

#include "engine/core/error.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace specula {

namespace {

// The first number of /proc/meminfo's `key` line, in bytes.
std::optional<std::uint64_t> meminfoBytes(const std::string& key) {
    std::ifstream in("/proc/meminfo");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind(key + ":", 0) == 0) {
            std::istringstream fields(line.substr(key.size() + 1));
            std::uint64_t kib = 0;
            if (fields >> kib) return kib * 1024;
        }
    return std::nullopt;
}

// A number in a cgroup v2 file ("max": none).
std::optional<std::uint64_t> cgroupNumber(const char* file) {
    std::ifstream in(std::string("/sys/fs/cgroup/") + file);
    std::uint64_t v = 0;
    if (in >> v) return v;
    return std::nullopt;
}

std::string gib(std::uint64_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f GiB", double(bytes) / double(1ull << 30));
    return text;
}

} // namespace

std::optional<std::uint64_t> availableMemoryBytes() {
    std::optional<std::uint64_t> available = meminfoBytes("MemAvailable");
    const std::optional<std::uint64_t> limit = cgroupNumber("memory.max"),
                                       used = cgroupNumber("memory.current");
    if (limit && used) {
        const std::uint64_t left = *limit > *used ? *limit - *used : 0;
        available = available ? std::min(*available, left) : left;
    }
    // A node shared with other jobs: the user's own bound (a positive decimal in MiB).
    if (const char* cap = std::getenv("SPECULA_MEMORY_LIMIT_MIB")) {
        char* end = nullptr;
        const unsigned long long mib = std::strtoull(cap, &end, 10);
        if (end != cap && *end == '\0' && mib > 0) {
            const std::uint64_t bytes = std::uint64_t(mib) << 20;
            available = available ? std::min(*available, bytes) : bytes;
        }
    }
    return available;
}

std::uint64_t cubeLayersBytes(int faceRes, std::uint64_t layers) {
    return layers * 6 * std::uint64_t(faceRes) * std::uint64_t(faceRes) * 4 * sizeof(float);
}

void checkMemoryFor(std::uint64_t bytes, const std::string& what, const std::string& file,
                    const std::string& field) {
    const std::optional<std::uint64_t> available = availableMemoryBytes();
    if (available && bytes > *available)
        throw Error(file, field,
                    what + " needs " + gib(bytes) + " for its faces; " + gib(*available) +
                        " of memory is available: lower --face-res");
}

} // namespace specula
