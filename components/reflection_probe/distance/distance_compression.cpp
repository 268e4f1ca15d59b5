#include "distance_compression.h"

#include "components/reflection_probe/distance/distance_layer_tiles.h"
#include "engine/image/bc6h.h"

namespace specula {

void roundTripLayersThroughBc6h(DistanceProbeAsset& asset) {
    const bool half = allLayersFitHalf(asset);
    for (DistanceProbeLayer& layer : asset.layers)
        for (Image& face : layer.faces) {
            const Image radiance = decodeBC6H(encodeBC6H(face), face.width, face.height);
            for (std::size_t t = 0; t < std::size_t(face.width) * std::size_t(face.height); ++t) {
                float* p = &face.pixels[t * std::size_t(face.channels)];
                for (std::size_t c = 0; c < 3; ++c)
                    p[c] = radiance.pixels[t * 3 + c];
                if (half && face.channels == 4) p[3] = roundToHalf(p[3]);
            }
        }
}

std::size_t cubeBytesRgba32f(int faceRes) {
    return 6 * std::size_t(faceRes) * std::size_t(faceRes) * 16;
}

std::size_t cubeBytesRgba16f(int faceRes) {
    return 6 * std::size_t(faceRes) * std::size_t(faceRes) * 8;
}

std::size_t cubeBytesBc6hR16f(int faceRes) {
    return 6 * (bc6hBytes(faceRes, faceRes) + std::size_t(faceRes) * std::size_t(faceRes) * 2);
}

} // namespace specula
