#include "pem_compression.h"

#include "components/reflection_probe/pem/pem_map_levels.h"
#include "engine/core/error.h"
#include "engine/image/bc6h.h"

#include <tbb/parallel_for.h>

namespace specula {

void compressPemMaps(PemAsset& asset) {
    if (asset.compression == PemCompression::Bc6h) return;
    tbb::parallel_for(std::size_t(0), asset.samples.size(), [&](std::size_t k) {
        PemSampleMap& s = asset.samples[k];
        s.blocks.clear();
        for (int level = 0; level < s.map.levels; ++level) {
            const int n = PemMap::levelRes(s.map.faceRes, level);
            s.blocks.push_back(encodeBC6HFaces(pemStackLevel(s.map, level), 6));
            pemUnstackLevel(decodeBC6HFaces(s.blocks.back(), n, n, 6), level, s.map);
        }
    });
    asset.compression = PemCompression::Bc6h;
}

void checkPemBlocks(const PemAsset& asset, const std::vector<std::string>& files) {
    if (asset.compression != PemCompression::Bc6h) return;
    for (std::size_t k = 0; k < asset.samples.size(); ++k) {
        const PemSampleMap& s = asset.samples[k];
        for (int level = 0; level < s.map.levels; ++level) {
            const int n = PemMap::levelRes(s.map.faceRes, level);
            const Image decoded = decodeBC6HFaces(s.blocks.at(std::size_t(level)), n, n, 6);
            const Image stored = pemStackLevel(s.map, level);
            if (decoded.pixels != stored.pixels)
                throw Error(files.at(k), "radiance",
                            "sample " + std::to_string(k) + " level " + std::to_string(level) +
                                " differs from its BC6H blocks' decoding (compress with "
                                "compressPemMaps)");
        }
    }
}

} // namespace specula
