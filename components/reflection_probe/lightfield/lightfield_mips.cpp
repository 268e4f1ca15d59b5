#include "lightfield_mips.h"

#include "engine/image/srgb.h"

#include <algorithm>
#include <cmath>

namespace specula {

int lightFieldMaxLevel(int res, LightFieldCompression c) {
    const int block = c == LightFieldCompression::BC1 ? 4 : 1;
    int level = 0;
    for (int tile = res; tile % 2 == 0 && (tile / 2) % block == 0; tile /= 2)
        ++level;
    return level;
}

std::size_t LightFieldMips::gpuBytes(int atlasSize, LightFieldCompression c) const {
    std::size_t bytes = 0;
    for (int k = 1; k <= maxLevel(); ++k) {
        const std::size_t n = std::size_t(atlasSize >> k);
        bytes += 6 * (c == LightFieldCompression::BC1 ? n * n / 2 : n * n * 4);
    }
    return bytes;
}

LightFieldMips buildLightFieldMips(const LightFieldAsset& a) {
    std::array<std::vector<std::uint8_t>, 6> codes;
    const int n = a.atlasSize();
    for (int k = 0; k < 6; ++k) {
        const std::vector<std::uint8_t>& stored = a.slabs[std::size_t(k)].data;
        codes[std::size_t(k)] =
            a.compression == LightFieldCompression::BC1 ? decodeBC1(stored.data(), n, n) : stored;
    }
    return buildLightFieldMips(codes, a.cameras, a.res, a.compression);
}

LightFieldMips buildLightFieldMips(const std::array<std::vector<std::uint8_t>, 6>& codes,
                                   int cameras, int res, LightFieldCompression c) {
    const int maxLevel = lightFieldMaxLevel(res, c);
    const bool bc1 = c == LightFieldCompression::BC1;
    float toLinear[256];
    for (int i = 0; i < 256; ++i)
        toLinear[i] = srgbToLinearValue(float(i) / 255.f);
    LightFieldMips mips;
    mips.levels.resize(std::size_t(maxLevel));
    for (int slab = 0; slab < 6; ++slab) {
        const std::vector<std::uint8_t>& level0 = codes[std::size_t(slab)];
        std::vector<float> linear(level0.size());
        for (std::size_t i = 0; i < level0.size(); ++i)
            linear[i] = toLinear[level0[i]];
        int n = cameras * res;
        for (int k = 1; k <= maxLevel; ++k) {
            // Tiles of RES / 2^(k-1) texels are even, so a 2x2 box never straddles two tiles.
            const int m = n / 2;
            std::vector<float> next(std::size_t(m) * std::size_t(m) * 3);
            std::vector<std::uint8_t> out(next.size());
            for (int y = 0; y < m; ++y)
                for (int x = 0; x < m; ++x)
                    for (int c = 0; c < 3; ++c) {
                        auto at = [&](int xx, int yy) {
                            return linear[(std::size_t(yy) * std::size_t(n) + std::size_t(xx)) * 3 +
                                          std::size_t(c)];
                        };
                        const float v = 0.25f * (at(2 * x, 2 * y) + at(2 * x + 1, 2 * y) +
                                                 at(2 * x, 2 * y + 1) + at(2 * x + 1, 2 * y + 1));
                        const std::size_t i =
                            (std::size_t(y) * std::size_t(m) + std::size_t(x)) * 3 + std::size_t(c);
                        next[i] = v;
                        out[i] = std::uint8_t(
                            std::lround(255.f * linearToSrgbValue(std::clamp(v, 0.f, 1.f))));
                    }
            mips.levels[std::size_t(k - 1)][std::size_t(slab)] =
                bc1 ? encodeBC1(out.data(), m, m) : std::move(out);
            linear = std::move(next);
            n = m;
        }
    }
    return mips;
}

} // namespace specula
