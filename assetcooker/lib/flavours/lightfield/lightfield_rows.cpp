#include "assetcooker/lib/flavours/lightfield/lightfield_rows.h"

#include "assetcooker/lib/os/binary_file.h"
#include "engine/core/error.h"
#include "engine/core/file_write.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

namespace specula {

namespace {

using binary::put;
using binary::Reader;

constexpr char kMagic[8] = {'S', 'P', 'L', 'F', 'R', 'O', 'W', 'S'};
constexpr std::uint32_t kVersion = 1;

void expectInt(const std::string& file, const std::string& field, std::int32_t got, int want) {
    if (got != want)
        throw Error(file, field,
                    "expected " + std::to_string(want) + ", got " + std::to_string(got) +
                        " (a block of another bake or shard list)");
}

} // namespace

void LightFieldDepthHistogram::add(float depth, bool hit) {
    ++total;
    if (!hit) {
        ++sky;
        return;
    }
    if (!(depth > 0.f)) {
        ++intruding;
        return;
    }
    minDepth = std::min(minDepth, depth);
    maxDepth = std::max(maxDepth, depth);
    // Clamped before the conversion: a depth near 0 (a hit just past the plane) would
    // overflow int. The same bins as std::min(int(q), kBins - 1) wherever that is defined.
    const float q = 1.f / depth / qMax * float(kBins);
    const int bin = q >= float(kBins - 1) ? kBins - 1 : int(q);
    ++bins[std::size_t(bin)];
}

void LightFieldDepthHistogram::merge(const LightFieldDepthHistogram& o) {
    for (int i = 0; i < kBins; ++i)
        bins[std::size_t(i)] += o.bins[std::size_t(i)];
    sky += o.sky, intruding += o.intruding, total += o.total;
    minDepth = std::min(minDepth, o.minDepth);
    maxDepth = std::max(maxDepth, o.maxDepth);
}

float LightFieldDepthHistogram::quantileQ(double f) const {
    const std::uint64_t n = total - intruding;
    if (n == 0) return 0.f;
    const double want = f * double(n);
    double seen = double(sky);
    if (seen > want) return 0.f;
    for (int i = 0; i < kBins; ++i) {
        seen += double(bins[std::size_t(i)]);
        if (seen > want) return (float(i) + 0.5f) / float(kBins) * qMax;
    }
    return qMax;
}

std::size_t lightFieldRowsBytes(int cameras, int res, int j0, int j1) {
    const std::size_t n = std::size_t(cameras) * std::size_t(res);
    return std::size_t(j1 - j0) * std::size_t(res) * n * 3;
}

void writeLightFieldRows(const LightFieldRows& r, const std::string& file) {
    const LightFieldDepthHistogram& h = r.histogram;
    if (h.bins.size() != std::size_t(LightFieldDepthHistogram::kBins) ||
        r.rgb.size() != lightFieldRowsBytes(r.cameras, r.res, r.j0, r.j1))
        throw Error(file, "", "cannot write: the block's histogram or bytes have the wrong size");
    std::string out(kMagic, sizeof kMagic);
    out.reserve(128 + h.bins.size() * 8 + r.rgb.size());
    put(out, kVersion);
    for (const int v : {r.slab, r.j0, r.j1, r.cameras, r.res})
        put(out, std::int32_t(v));
    put(out, h.qMax);
    put(out, h.sky), put(out, h.intruding), put(out, h.total);
    put(out, h.minDepth), put(out, h.maxDepth);
    put(out, std::uint32_t(h.bins.size()));
    for (const std::uint64_t b : h.bins)
        put(out, b);
    put(out, std::uint64_t(r.rgb.size()));
    out.append(reinterpret_cast<const char*>(r.rgb.data()), r.rgb.size());
    writeFileAtomically(file, out);
}

LightFieldRows readLightFieldRows(const std::string& file, int slab, int j0, int j1, int cameras,
                                  int res) {
    const std::string bytes = binary::readAll(file);
    Reader r(file, bytes);
    r.need(sizeof kMagic, "magic");
    if (std::memcmp(r.here(), kMagic, sizeof kMagic) != 0)
        throw Error(file, "magic", "expected a specula light-field rows file (SPLFROWS)");
    r.skip(sizeof kMagic);
    const std::uint32_t version = r.get<std::uint32_t>("version");
    if (version != kVersion)
        throw Error(file, "version",
                    "expected " + std::to_string(kVersion) + ", got " + std::to_string(version));
    LightFieldRows out;
    expectInt(file, "slab", out.slab = r.get<std::int32_t>("slab"), slab);
    expectInt(file, "j0", out.j0 = r.get<std::int32_t>("j0"), j0);
    expectInt(file, "j1", out.j1 = r.get<std::int32_t>("j1"), j1);
    expectInt(file, "cameras", out.cameras = r.get<std::int32_t>("cameras"), cameras);
    expectInt(file, "res", out.res = r.get<std::int32_t>("res"), res);
    if (slab < 0 || slab >= 6 || j0 < 0 || j1 <= j0 || j1 > cameras || res < 1)
        throw Error(file, "j1", "expected 0 <= j0 < j1 <= cameras and a slab 0 .. 5");
    LightFieldDepthHistogram& h = out.histogram;
    h.qMax = r.get<float>("q_max");
    if (!(std::isfinite(h.qMax) && h.qMax > 0.f))
        throw Error(file, "q_max", "expected a finite number > 0");
    h.sky = r.get<std::uint64_t>("sky");
    h.intruding = r.get<std::uint64_t>("intruding");
    h.total = r.get<std::uint64_t>("total");
    h.minDepth = r.get<float>("min_depth");
    h.maxDepth = r.get<float>("max_depth");
    if (std::isnan(h.minDepth) || std::isnan(h.maxDepth))
        throw Error(file, "min_depth", "expected numbers, got NaN");
    const std::uint32_t binCount = r.get<std::uint32_t>("bins");
    if (binCount != std::uint32_t(LightFieldDepthHistogram::kBins))
        throw Error(file, "bins",
                    "expected " + std::to_string(LightFieldDepthHistogram::kBins) + ", got " +
                        std::to_string(binCount));
    r.need(std::size_t(binCount) * 8, "bins");
    std::uint64_t binned = 0;
    for (std::uint64_t& b : h.bins) {
        b = r.get<std::uint64_t>("bins");
        binned += b;
    }
    // Every sample went to exactly one of sky, intruding and the bins; no more samples than
    // the block's rays.
    const std::uint64_t rays =
        std::uint64_t(j1 - j0) * std::uint64_t(cameras) * std::uint64_t(res) * std::uint64_t(res);
    if (h.sky > rays || h.intruding > rays || binned > rays ||
        h.sky + h.intruding + binned != h.total || h.total > rays)
        throw Error(file, "total",
                    "the counts do not add up: sky + intruding + bins != total, or more samples "
                    "than the block's " +
                        std::to_string(rays) + " rays");
    const std::uint64_t byteCount = r.get<std::uint64_t>("bytes");
    const std::size_t want = lightFieldRowsBytes(cameras, res, j0, j1);
    if (byteCount != want)
        throw Error(file, "bytes",
                    "expected " + std::to_string(want) + " bytes of camera rows " +
                        std::to_string(j0) + " .. " + std::to_string(j1 - 1) + ", got " +
                        std::to_string(byteCount));
    r.need(want, "bytes");
    out.rgb.assign(reinterpret_cast<const std::uint8_t*>(r.here()),
                   reinterpret_cast<const std::uint8_t*>(r.here()) + want);
    r.skip(want);
    if (r.left() != 0)
        throw Error(file, "bytes", std::to_string(r.left()) + " bytes after the block's end");
    return out;
}

} // namespace specula
