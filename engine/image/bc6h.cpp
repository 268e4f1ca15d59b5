#include "bc6h.h"
#include "bc6h_format.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

namespace specula {

using namespace bc6h_detail;

namespace {

// The mode of a block; -1 for the reserved ones.
int modeOf(const std::uint8_t* block) {
    const unsigned two = block[0] & 3u;
    if (two < 2) return int(two);
    const unsigned five = block[0] & 31u;
    for (std::size_t m = 2; m < kModes.size(); ++m)
        if (kModes[m].value == five) return int(m);
    return -1;
}

int signExtend(int v, int bits) {
    const int sign = 1 << (bits - 1);
    return (v & (sign - 1)) - (v & sign);
}

void decodeBlock(const std::uint8_t* block, std::array<std::array<std::uint16_t, 3>, 16>& out) {
    const int m = modeOf(block);
    if (m < 0) {
        for (auto& t : out)
            t = {0, 0, 0};
        return;
    }
    const Mode& mode = kModes[std::size_t(m)];
    const ModeHeader& header = modeHeaders()[std::size_t(m)];
    std::array<std::array<int, 3>, 4> e{};
    int partition = 0;
    for (int i = 0; i < header.count; ++i) {
        const BitRef r = header.refs[std::size_t(i)];
        const int v = int(bitAt(block, mode.modeBits + i)) << r.bit;
        if (r.field == kPartitionField)
            partition |= v;
        else
            e[r.field / 3u][r.field % 3u] |= v;
    }
    const int endpoints = 2 * mode.regions;
    const int mask = (1 << mode.endpointBits) - 1;
    for (int c = 0; c < 3; ++c) {
        if (mode.transformed)
            for (int k = 1; k < endpoints; ++k)
                e[std::size_t(k)][std::size_t(c)] =
                    (e[0][std::size_t(c)] + signExtend(e[std::size_t(k)][std::size_t(c)],
                                                       mode.deltaBits[std::size_t(c)])) &
                    mask;
        for (int k = 0; k < endpoints; ++k)
            e[std::size_t(k)][std::size_t(c)] =
                unquantize(e[std::size_t(k)][std::size_t(c)], mode.endpointBits);
    }
    const bool two = mode.regions == 2;
    int pos = two ? 82 : 65;
    for (int i = 0; i < 16; ++i) {
        const bool anchor = i == 0 || (two && i == kAnchor2[std::size_t(partition)]);
        const int bits = (two ? 3 : 4) - (anchor ? 1 : 0);
        int index = 0;
        for (int b = 0; b < bits; ++b)
            index |= int(bitAt(block, pos++)) << b;
        const int region = two ? (kPartitions[std::size_t(partition)] >> i) & 1 : 0;
        const int w = two ? kWeights3[std::size_t(index)] : kWeights4[std::size_t(index)];
        for (std::size_t c = 0; c < 3; ++c)
            out[std::size_t(i)][c] =
                interpolate(e[std::size_t(2 * region)][c], e[std::size_t(2 * region + 1)][c], w);
    }
}

std::uint16_t halfBitsOf(float v) {
    if (!(v > 0.f)) return 0; // negative, zero, NaN
    return std::uint16_t(glm::packHalf1x16(std::min(v, 65504.f)));
}

} // namespace

std::size_t bc6hBytes(int width, int height) {
    return std::size_t((width + 3) / 4) * std::size_t((height + 3) / 4) * kBc6hBlockBytes;
}

std::vector<std::uint8_t> encodeBC6H(const Image& image) {
    const int bw = (image.width + 3) / 4, bh = (image.height + 3) / 4;
    std::vector<std::uint8_t> out(bc6hBytes(image.width, image.height));
    for (int by = 0; by < bh; ++by)
        for (int bx = 0; bx < bw; ++bx) {
            Texels t{};
            for (int i = 0; i < 16; ++i) {
                const int x = std::min(4 * bx + i % 4, image.width - 1);
                const int y = std::min(4 * by + i / 4, image.height - 1);
                const float* p = image.at(x, y);
                for (int c = 0; c < 3; ++c)
                    t[std::size_t(i)][std::size_t(c)] = c < image.channels ? halfBitsOf(p[c]) : 0;
            }
            encodeBlock(
                t, &out[(std::size_t(by) * std::size_t(bw) + std::size_t(bx)) * kBc6hBlockBytes]);
        }
    return out;
}

std::vector<std::uint16_t> decodeBC6HHalf(std::span<const std::uint8_t> blocks, int width,
                                          int height) {
    if (width < 0 || height < 0 || blocks.size() != bc6hBytes(width, height))
        throw std::invalid_argument("decodeBC6H: " + std::to_string(blocks.size()) +
                                    " bytes of blocks for a " + std::to_string(width) + "x" +
                                    std::to_string(height) + " image");
    std::vector<std::uint16_t> out(std::size_t(width) * std::size_t(height) * 3);
    const int bw = (width + 3) / 4, bh = (height + 3) / 4;
    std::array<std::array<std::uint16_t, 3>, 16> texels{};
    for (int by = 0; by < bh; ++by)
        for (int bx = 0; bx < bw; ++bx) {
            decodeBlock(
                &blocks[(std::size_t(by) * std::size_t(bw) + std::size_t(bx)) * kBc6hBlockBytes],
                texels);
            for (int i = 0; i < 16; ++i) {
                const int x = 4 * bx + i % 4, y = 4 * by + i / 4;
                if (x >= width || y >= height) continue;
                std::copy(texels[std::size_t(i)].begin(), texels[std::size_t(i)].end(),
                          &out[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3]);
            }
        }
    return out;
}

Image decodeBC6H(std::span<const std::uint8_t> blocks, int width, int height) {
    const std::vector<std::uint16_t> half = decodeBC6HHalf(blocks, width, height);
    Image image(width, height, 3);
    for (std::size_t i = 0; i < half.size(); ++i)
        image.pixels[i] = glm::unpackHalf1x16(half[i]);
    return image;
}

std::vector<std::uint8_t> encodeBC6HFaces(const Image& stacked, int faces) {
    const int h = stacked.height / faces;
    const auto faceValues = std::ptrdiff_t(stacked.width) * h * stacked.channels;
    std::vector<std::uint8_t> blocks;
    for (int f = 0; f < faces; ++f) {
        Image face(stacked.width, h, stacked.channels);
        std::copy_n(stacked.pixels.begin() + std::ptrdiff_t(f) * faceValues, faceValues,
                    face.pixels.begin());
        const std::vector<std::uint8_t> b = encodeBC6H(face);
        blocks.insert(blocks.end(), b.begin(), b.end());
    }
    return blocks;
}

Image decodeBC6HFaces(std::span<const std::uint8_t> blocks, int width, int faceHeight, int faces) {
    Image level(width, faceHeight * faces, 3);
    const std::size_t faceBytes = bc6hBytes(width, faceHeight);
    if (blocks.size() != faceBytes * std::size_t(faces))
        throw std::invalid_argument("decodeBC6HFaces: " + std::to_string(blocks.size()) +
                                    " bytes for " + std::to_string(faces) + " faces of " +
                                    std::to_string(faceBytes));
    for (int f = 0; f < faces; ++f) {
        const Image face =
            decodeBC6H(blocks.subspan(std::size_t(f) * faceBytes, faceBytes), width, faceHeight);
        std::copy(face.pixels.begin(), face.pixels.end(),
                  level.pixels.begin() + std::ptrdiff_t(f) * std::ptrdiff_t(face.pixels.size()));
    }
    return level;
}

} // namespace specula
