#pragma once
// Memory checked before it is allocated: a bake whose faces would not fit is refused with the
// figures, where it used to die on a bare std::bad_alloc (or the kernel's OOM killer) after
// minutes. Linux: MemAvailable from /proc/meminfo, bounded by the cgroup's memory.max and by
// SPECULA_MEMORY_LIMIT_MIB when set (a farm node shared with other jobs).
#include <cstdint>
#include <optional>
#include <string>

namespace specula {

// Bytes this process may still allocate, as the kernel estimates them; none when unknown.
std::optional<std::uint64_t> availableMemoryBytes();

// Float RGBA cube faces of `layers` cube maps at `faceRes`: what a distance bake holds.
std::uint64_t cubeLayersBytes(int faceRes, std::uint64_t layers);

// Throws Error(file, field) when `bytes` exceed the memory available, naming both in GiB and
// `what` needs them (e.g. "a bake at face_res 4096 with 15 layers").
void checkMemoryFor(std::uint64_t bytes, const std::string& what, const std::string& file,
                    const std::string& field);

} // namespace specula
