#include "distance_compression.h"

#include "components/reflection_probe/distance/distance_layer_tiles.h"
#include "components/reflection_probe/distance/distance_probe.h"
#include "engine/image/bc6h.h"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

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

bool compositeDistanceFitsHalf(const DistanceProbeAsset& asset, float tolerance) {
    if (asset.layers.empty() || roundToHalf(asset.dInf) != asset.dInf) return false;
    float farthest = 0.f;
    for (const Image& face : asset.layers[0].faces)
        for (std::size_t i = 3; i < face.pixels.size(); i += std::size_t(face.channels)) {
            const float d = face.pixels[i];
            if (d < 0x1p-14f) return false;
            if (d < asset.dInf) farthest = std::max(farthest, d);
        }
    const float step = farthest > 0.f ? std::exp2(std::floor(std::log2(farthest)) - 10.f) : 0.f;
    return step <= tolerance;
}

float cookedLookupTolerance(const DistanceProbeAsset& asset) {
    const nlohmann::json plan = nlohmann::json::parse(asset.effectPlan, nullptr, false);
    if (plan.is_object() && plan.contains("lookup") && plan["lookup"].is_object()) {
        const nlohmann::json& t = plan["lookup"].value("tolerance", nlohmann::json());
        if (t.is_number() && t.get<double>() > 0.0 && std::isfinite(t.get<double>()))
            return t.get<float>();
    }
    return DistanceProbe{}.errorTolerance;
}

namespace {

// Each face's radiance encoded to BC6H (the blocks, faces in order, returned) and replaced by
// its decoding; A rounded to half floats when `half`. A glossy level's A is the nearest of the
// composite's distances under it: rounded alike (rounding keeps order), it stays exactly that.
std::vector<std::uint8_t> compressRadiance(std::array<Image, 6>& faces, bool half) {
    std::vector<std::uint8_t> blocks;
    for (Image& face : faces) {
        const std::vector<std::uint8_t> b = encodeBC6H(face);
        const Image radiance = decodeBC6H(b, face.width, face.height);
        blocks.insert(blocks.end(), b.begin(), b.end());
        for (std::size_t t = 0; t < std::size_t(face.width) * std::size_t(face.height); ++t) {
            float* p = &face.pixels[t * std::size_t(face.channels)];
            for (std::size_t c = 0; c < 3; ++c)
                p[c] = radiance.pixels[t * 3 + c];
            if (half) p[3] = roundToHalf(p[3]);
        }
    }
    return blocks;
}

} // namespace

void compressComposite(DistanceProbeAsset& asset) {
    if (asset.compression == DistanceCompression::Bc6h || asset.layers.empty()) return;
    const bool half = compositeDistanceFitsHalf(asset, cookedLookupTolerance(asset));
    DistanceProbeLayer& composite = asset.layers[0];
    std::vector<std::uint8_t> blocks = compressRadiance(composite.faces, half);
    std::vector<std::vector<std::uint8_t>> glossyBlocks;
    for (std::array<Image, 6>& level : asset.glossyLevels)
        glossyBlocks.push_back(compressRadiance(level, half));
    const DistanceLayerContent c = measureDistanceLayer(composite.faces, asset.dInf, "layer 0");
    composite.minDistance = c.minDistance;
    composite.maxDistance = c.maxDistance;
    composite.solidAngle = float(c.solidAngle);
    if (c.solidAngle > 0.0)
        composite.avgDistance = std::clamp(composite.avgDistance, c.minDistance, c.maxDistance);
    asset.compression = DistanceCompression::Bc6h;
    asset.compositeBlocks = std::move(blocks);
    asset.glossyBlocks = std::move(glossyBlocks);
    asset.halfCompositeDistance = half;
}

std::size_t compositeBytes(const DistanceProbeAsset& asset) {
    if (asset.compression == DistanceCompression::None) return cubeBytesRgba32f(asset.faceRes);
    const std::size_t n = std::size_t(asset.faceRes);
    return asset.compositeBlocks.size() + 6 * n * n * (asset.halfCompositeDistance ? 2 : 4);
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
