// A compressed probe's composite on disk (DistanceCompression::Bc6h, asset format 3.0): its
// radiance a BC6H KTX2 cube (layer_00.ktx2), its distance a one-channel R16F or R32F KTX2 cube
// (layer_00_distance.ktx2) named in the layer's "distance": {"file", "checksum"}. Its
// reader and checks; the writer is writer/distance_probe_writer.cpp.
#include "distance_asset_internal.h"

#include "components/reflection_probe/distance/distance_layer_tiles.h"
#include "engine/core/error.h"
#include "engine/image/bc6h.h"
#include "engine/image/ktx2.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace specula::distance_asset {

namespace {

// That `blocks` decode to exactly the faces' RGB, and (`halfDistance`) their A are halves.
void checkBlocks(const std::array<Image, 6>& faces, const std::vector<std::uint8_t>& stored,
                 bool halfDistance, const std::string& file) {
    const int n = faces[0].width;
    const std::size_t faceBytes = bc6hBytes(n, n);
    if (stored.size() != 6 * faceBytes)
        throw Error(file, "blocks",
                    "holds " + std::to_string(stored.size()) + " bytes of BC6H, " +
                        std::to_string(6 * faceBytes) + " expected for six faces of " +
                        std::to_string(n));
    const std::span<const std::uint8_t> blocks(stored);
    for (int f = 0; f < 6; ++f) {
        const Image decoded =
            decodeBC6H(blocks.subspan(std::size_t(f) * faceBytes, faceBytes), n, n);
        const Image& face = faces[std::size_t(f)];
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const float* p = face.at(x, y);
                const float* q = decoded.at(x, y);
                if (p[0] != q[0] || p[1] != q[1] || p[2] != q[2])
                    throw Error(file, "radiance",
                                texelName(f, x, y) +
                                    " differs from its BC6H blocks' decoding (compress with "
                                    "compressComposite)");
                if (halfDistance && roundToHalf(p[3]) != p[3])
                    throw Error(file, "distance",
                                texelName(f, x, y) + " holds " + shortNumber(p[3]) +
                                    ", which no half float holds");
            }
    }
}

} // namespace

void checkCompressedComposite(const DistanceProbeAsset& a, const std::string& file,
                              const std::vector<std::string>& glossyFiles) {
    checkBlocks(a.layers.at(0).faces, a.compositeBlocks, a.halfCompositeDistance, file);
    if (a.glossyBlocks.size() != a.glossyLevels.size())
        throw Error(file, "glossy",
                    std::to_string(a.glossyBlocks.size()) + " levels of BC6H blocks for " +
                        std::to_string(a.glossyLevels.size()) + " glossy levels");
    for (std::size_t k = 0; k < a.glossyLevels.size(); ++k)
        checkBlocks(a.glossyLevels[k], a.glossyBlocks[k], false, glossyFiles.at(k));
}

std::array<Image, 6> readCompressedComposite(const ManifestFields& r, const json& layer,
                                             const std::string& path, const fs::path& dir,
                                             const std::string& radianceFile,
                                             DistanceProbeAsset& a) {
    const int n = a.faceRes;
    Ktx2Texture radiance =
        readKtx2(radianceFile, {.width = n, .height = n, .faces = 6, .channels = 3});
    if (!radiance.bc6h)
        throw Error(radianceFile, "vkFormat",
                    "expected BC6H blocks: the manifest's compression is \"bc6h\"");
    const json& entry = r.member(layer, "distance", path);
    const ManifestFields::CheckedFile distanceFile =
        r.checkedFile(entry, path + "distance.", dir, maxLayerFileBytes(n));
    const Ktx2Texture distance = r.namedFile(path + "distance.", [&] {
        return readKtx2(distanceFile.path, {.width = n, .height = n, .faces = 6, .channels = 1});
    });
    if (distance.bc6h)
        throw Error(distanceFile.path, "vkFormat", "expected R16F or R32F distances");
    const Image& rgb = radiance.levels[0];
    const Image& d = distance.levels[0];
    Image stacked(n, 6 * n, 4);
    for (int y = 0; y < 6 * n; ++y)
        for (int x = 0; x < n; ++x) {
            float* p = stacked.at(x, y);
            const float* c = rgb.at(x, y);
            p[0] = c[0], p[1] = c[1], p[2] = c[2], p[3] = d.at(x, y)[0];
        }
    a.compression = DistanceCompression::Bc6h;
    a.compositeBlocks = std::move(radiance.blocks[0]);
    a.halfCompositeDistance = distance.halfFloat;
    return splitFaces(stacked);
}

} // namespace specula::distance_asset
