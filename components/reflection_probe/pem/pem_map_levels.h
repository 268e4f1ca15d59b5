#pragma once
// The MIP levels of a PEM's distant maps (Hakura, Snyder, Lengyel 2001, §4 "EM MIPMAPs"): the
// cooker infers every level together, so the levels are not filtered copies of each other;
// these are the plain box-filtered chain (what a renderer would make on the fly from level
// 0: the reference the inferred levels are measured against, and each level's prior), and
// the per-level images the asset stores.
#include "components/reflection_probe/pem/pem_lookup_cpu.h"
#include "engine/image/image.h"

#include <cstddef>
#include <string>
#include <vector>

namespace specula {

// Calls f(parent, children, count) for every texel `parent` of levels 1 .. levels-1 (texel
// indices as PemMap's), in order, with the `count` texels of the level above that it covers:
// 2 x 2, or 3 along an axis whose size is odd (its last texel joins the last pair).
template <class F> void forEachPemLevelParent(int faceRes, int levels, F f) {
    for (int k = 1; k < levels; ++k) {
        const int up = PemMap::levelRes(faceRes, k - 1), n = PemMap::levelRes(faceRes, k);
        const int upOffset = PemMap::levelOffset(faceRes, k - 1);
        const int offset = PemMap::levelOffset(faceRes, k);
        for (int face = 0; face < 6; ++face)
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) {
                    const int i1 = (i == n - 1) ? up - 1 : 2 * i + 1;
                    const int j1 = (j == n - 1) ? up - 1 : 2 * j + 1;
                    int children[9], count = 0;
                    for (int y = 2 * j; y <= j1; ++y)
                        for (int x = 2 * i; x <= i1; ++x)
                            children[count++] = upOffset + (face * up + y) * up + x;
                    f(offset + (face * n + j) * n + i, children, count);
                }
    }
}

// Level 0's texels (6 N^2) followed by levels 1 .. levels-1, each texel the mean of the
// (up to four: a face of odd size folds its last row and column in) texels of the level above
// that it covers, as glGenerateMipmap's box filter reads them. levels in 1 .. maxLevels(N).
std::vector<glm::vec3> pemBoxFilteredLevels(const std::vector<glm::vec3>& level0, int faceRes,
                                            int levels);

// `map` (its level 0) with `levels` levels of pemBoxFilteredLevels.
PemMap pemFilteredMips(const PemMap& map, int levels);

// Level `level` of `map` as an n x 6n RGB image (n = levelRes), faces stacked as the
// asset's sample files; and back into `map`'s texels (the image already checked n x 6n).
Image pemStackLevel(const PemMap& map, int level);
void pemUnstackLevel(const Image& img, int level, PemMap& map);

// sample_NN_mipK.ktx2: level k >= 1 of sample NN (level 0 is sample_NN.ktx2).
std::string pemLevelFileName(std::size_t sample, int level);

} // namespace specula
