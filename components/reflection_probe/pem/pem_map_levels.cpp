#include "pem_map_levels.h"

#include <algorithm>
#include <cstdio>

namespace specula {

std::vector<glm::vec3> pemBoxFilteredLevels(const std::vector<glm::vec3>& level0, int faceRes,
                                            int levels) {
    std::vector<glm::vec3> out(std::size_t(PemMap::texelCount(faceRes, levels)), glm::vec3(0.f));
    std::copy(level0.begin(), level0.begin() + PemMap::texelCount(faceRes), out.begin());
    forEachPemLevelParent(faceRes, levels, [&](int parent, const int* children, int count) {
        glm::vec3 sum(0.f);
        for (int c = 0; c < count; ++c)
            sum += out[std::size_t(children[c])];
        out[std::size_t(parent)] = sum / float(count);
    });
    return out;
}

PemMap pemFilteredMips(const PemMap& map, int levels) {
    PemMap out = map;
    out.texels = pemBoxFilteredLevels(map.texels, map.faceRes, levels);
    out.levels = levels;
    return out;
}

Image pemStackLevel(const PemMap& map, int level) {
    const int n = PemMap::levelRes(map.faceRes, level);
    const std::size_t offset = std::size_t(PemMap::levelOffset(map.faceRes, level));
    Image out(n, 6 * n, 3);
    for (std::size_t t = 0; t < std::size_t(PemMap::texelCount(n)); ++t)
        for (std::size_t c = 0; c < 3; ++c)
            out.pixels[t * 3 + c] = map.texels[offset + t][int(c)];
    return out;
}

void pemUnstackLevel(const Image& img, int level, PemMap& map) {
    const int n = PemMap::levelRes(map.faceRes, level);
    const std::size_t offset = std::size_t(PemMap::levelOffset(map.faceRes, level));
    map.texels.resize(std::max(map.texels.size(), offset + std::size_t(PemMap::texelCount(n))));
    for (std::size_t t = 0; t < std::size_t(PemMap::texelCount(n)); ++t) {
        const std::size_t p = t * std::size_t(img.channels);
        map.texels[offset + t] = glm::vec3(img.pixels[p], img.pixels[p + 1], img.pixels[p + 2]);
    }
}

std::string pemLevelFileName(std::size_t sample, int level) {
    char name[64];
    std::snprintf(name, sizeof name, "sample_%02zu_mip%d.ktx2", sample, level);
    return name;
}

} // namespace specula
