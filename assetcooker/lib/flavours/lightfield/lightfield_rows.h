#pragma once
// A block of a light-field probe's bake (docs/design.md §5, §9): slab s, camera rows j in [j0, j1),
// traced on its own (traceLightFieldRows, lightfield_bake.h) so a probe's bake can be split
// over machines. In the slab image (n = NUM * RES pixels a side, sRGB8) camera row j covers
// image rows j*RES .. (j+1)*RES - 1, so a block is one contiguous byte range. Its depth
// histogram merges with the others' exactly and in any order (integer counts, min and max):
// the blocks' assembly is byte-identical to the one-machine bake.
//
// The file (writeLightFieldRows): "SPLFROWS", then little-endian u32 version, i32 slab, j0,
// j1, cameras, res, f32 qMax, u64 sky, intruding, total, f32 minDepth, maxDepth, u32 bin
// count, u64 bins, u64 byte count, the bytes; nothing after.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace specula {

// Depth statistics of a slab over the samples whose line passes through the cell, binned in
// inverse depth (disparity is linear in 1/z, so that is where the percentiles matter).
struct LightFieldDepthHistogram {
    static constexpr int kBins = 8192;
    float qMax = 1.f; // 1 / the nearest depth binned apart
    std::vector<std::uint64_t> bins = std::vector<std::uint64_t>(kBins, 0);
    std::uint64_t sky = 0, intruding = 0, total = 0;
    float minDepth = std::numeric_limits<float>::infinity(), maxDepth = 0.f;

    void add(float depth, bool hit);
    void merge(const LightFieldDepthHistogram& o); // order-independent: exact in any order
    // Inverse depth at fraction f of the samples beyond the plane, the sky counting as q = 0.
    float quantileQ(double f) const;
};

struct LightFieldRows {
    int slab = 0;       // 0 .. 5
    int j0 = 0, j1 = 0; // camera rows [j0, j1)
    int cameras = 0;    // NUM
    int res = 0;        // RES
    LightFieldDepthHistogram histogram;
    std::vector<std::uint8_t> rgb; // image rows j0*RES .. j1*RES - 1 of the slab, sRGB8
};

// The bytes of camera rows [j0, j1): (j1 - j0) * RES * NUM * RES * 3.
std::size_t lightFieldRowsBytes(int cameras, int res, int j0, int j1);

// Writes `rows` to `file` atomically (written beside, then renamed). Throws Error naming it.
void writeLightFieldRows(const LightFieldRows& rows, const std::string& file);

// Reads a block and checks it against the shape expected (slab, rows, cameras, res) and
// against the file's own size: throws Error(file, field, what) on any mismatch, a wrong
// header, a truncated or overlong file, or counts that do not add up.
LightFieldRows readLightFieldRows(const std::string& file, int slab, int j0, int j1, int cameras,
                                  int res);

} // namespace specula
