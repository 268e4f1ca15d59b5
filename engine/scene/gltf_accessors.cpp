#include "gltf_accessors.h"

#include <algorithm>
#include <cstring>

namespace specula::gltf_internal {

namespace {

// Accessors without a bufferView allocate `count` elements from nothing but a number in
// the JSON; this caps what a hostile file can make us allocate that way.
constexpr std::size_t kMaxUnbackedElements = std::size_t(1) << 26;

std::size_t componentBytes(int componentType) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
        return 4;
    default:
        return 0;
    }
}

bool isSignedOrFloat(int componentType) {
    return componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
           componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
           componentType == TINYGLTF_COMPONENT_TYPE_SHORT;
}

// One component as double; `normalized` applies glTF's normalised-integer mapping.
double component(int type, const unsigned char* p, bool normalized) {
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        std::int8_t v;
        std::memcpy(&v, p, 1);
        return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return normalized ? p[0] / 255.0 : p[0];
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        std::int16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        std::uint32_t v;
        std::memcpy(&v, p, 4);
        return normalized ? v / 4294967295.0 : v;
    }
    default: {
        float v;
        std::memcpy(&v, p, 4);
        return v;
    }
    }
}

// How one accessor's elements are laid out, after its type checks.
struct Layout {
    std::size_t count = 0;
    int comps = 0;
    std::size_t componentSize = 0;
    bool normalized = false;
    std::size_t elementSize() const { return componentSize * std::size_t(comps); }
};

template <typename T>
void readElement(const tinygltf::Accessor& acc, const Layout& l, const unsigned char* src, T* dst) {
    for (int c = 0; c < l.comps; ++c)
        dst[c] = static_cast<T>(
            component(acc.componentType, src + std::size_t(c) * l.componentSize, l.normalized));
}

// Replaces the elements a sparse accessor lists, every index and range checked.
template <typename T>
void applySparse(const Context& ctx, const tinygltf::Accessor& acc, const Layout& l,
                 const std::string& af, std::vector<T>& out) {
    const auto& sp = acc.sparse;
    const std::string sf = af + ".sparse";
    if (sp.count < 0 || std::size_t(sp.count) > l.count)
        ctx.fail(sf + ".count", "sparse count " + std::to_string(sp.count) +
                                    " exceeds the accessor count " + std::to_string(l.count));
    const std::size_t n = std::size_t(sp.count);
    const int it = sp.indices.componentType;
    const std::size_t ib = componentBytes(it);
    if (ib == 0 || isSignedOrFloat(it))
        ctx.fail(sf + ".indices.componentType", "expected an unsigned integer type");
    if (sp.indices.byteOffset < 0 || sp.values.byteOffset < 0) ctx.fail(sf, "negative byteOffset");
    const Span is = viewRange(ctx, sp.indices.bufferView, std::size_t(sp.indices.byteOffset), n, ib,
                              false, sf + ".indices");
    const Span vs = viewRange(ctx, sp.values.bufferView, std::size_t(sp.values.byteOffset), n,
                              l.elementSize(), false, sf + ".values");
    for (std::size_t k = 0; k < n; ++k) {
        const double target = component(it, is.data + k * is.stride, false);
        if (target >= double(l.count))
            ctx.fail(sf + ".indices", "index out of range: " + std::to_string(target) +
                                          " >= count " + std::to_string(l.count));
        readElement(acc, l, vs.data + k * vs.stride,
                    &out[std::size_t(target) * std::size_t(l.comps)]);
    }
}

// Reads accessor `index` into `comps` values per element, fully range-checked,
// including sparse substitution.
template <typename T>
std::vector<T> readAccessor(const Context& ctx, int index, int comps, bool integerOnly,
                            const std::string& from) {
    const auto& acc = ctx.at(ctx.model().accessors, index, "accessors", from);
    const std::string af = idx("accessors", std::size_t(index));
    const int have = tinygltf::GetNumComponentsInType(std::uint32_t(acc.type));
    if (have != comps)
        ctx.fail(af + ".type", "expected " + std::string(comps == 1 ? "SCALAR" : "VEC") +
                                   (comps == 1 ? "" : std::to_string(comps)) + " for " + from);
    const Layout l{acc.count, comps, componentBytes(acc.componentType),
                   acc.normalized && !integerOnly};
    if (l.componentSize == 0 || (integerOnly && isSignedOrFloat(acc.componentType)))
        ctx.fail(af + ".componentType",
                 "unsupported componentType " + std::to_string(acc.componentType) + " for " + from);
    std::vector<T> out;
    if (acc.bufferView < 0) {
        if (l.count > kMaxUnbackedElements)
            ctx.fail(af + ".count", "count " + std::to_string(l.count) + " without a bufferView");
        out.assign(l.count * std::size_t(comps), T(0));
    } else {
        const Span s =
            viewRange(ctx, acc.bufferView, acc.byteOffset, l.count, l.elementSize(), true, af);
        out.resize(l.count * std::size_t(comps));
        for (std::size_t i = 0; i < l.count; ++i)
            readElement(acc, l, s.data + i * s.stride, &out[i * std::size_t(comps)]);
    }
    if (acc.sparse.isSparse) applySparse(ctx, acc, l, af, out);
    return out;
}

} // namespace

Span viewRange(const Context& ctx, int view, std::size_t offset, std::size_t count,
               std::size_t elemSize, bool useViewStride, const std::string& field) {
    const auto& bv = ctx.at(ctx.model().bufferViews, view, "bufferViews", field);
    const std::string vf = idx("bufferViews", std::size_t(view));
    const auto& buf = ctx.at(ctx.model().buffers, bv.buffer, "buffers", vf);
    if (bv.byteOffset > buf.data.size() || bv.byteLength > buf.data.size() - bv.byteOffset)
        ctx.fail(vf, "byteOffset " + std::to_string(bv.byteOffset) + " + byteLength " +
                         std::to_string(bv.byteLength) + " exceeds buffers[" +
                         std::to_string(bv.buffer) + "] size " + std::to_string(buf.data.size()));
    std::size_t stride = elemSize;
    if (useViewStride && bv.byteStride != 0) {
        if (bv.byteStride < elemSize)
            ctx.fail(vf, "byteStride " + std::to_string(bv.byteStride) +
                             " is smaller than the element size " + std::to_string(elemSize));
        stride = bv.byteStride;
    }
    if (count > 0) {
        // Overflow-safe form of offset + (count-1)*stride + elemSize <= byteLength.
        const bool fits = offset <= bv.byteLength && elemSize <= bv.byteLength - offset &&
                          (count - 1) <= (bv.byteLength - offset - elemSize) / stride;
        if (!fits)
            ctx.fail(field, "accessor out of range: " + std::to_string(count) + " elements of " +
                                std::to_string(elemSize) + " bytes, stride " +
                                std::to_string(stride) + ", from offset " + std::to_string(offset) +
                                " do not fit in " + vf + " (" + std::to_string(bv.byteLength) +
                                " bytes)");
    }
    return {buf.data.data() + bv.byteOffset + offset, stride};
}

Bytes viewBytes(const Context& ctx, int view, const std::string& field) {
    const auto& bv = ctx.at(ctx.model().bufferViews, view, "bufferViews", field + ".bufferView");
    const Span s = viewRange(ctx, view, 0, bv.byteLength > 0 ? 1 : 0, bv.byteLength, false, field);
    return {s.data, bv.byteLength};
}

std::vector<glm::vec3> readVec3(const Context& ctx, int index, const std::string& from) {
    const auto raw = readAccessor<float>(ctx, index, 3, false, from);
    std::vector<glm::vec3> v(raw.size() / 3);
    for (std::size_t i = 0; i < v.size(); ++i)
        v[i] = {raw[3 * i], raw[3 * i + 1], raw[3 * i + 2]};
    return v;
}

std::vector<glm::vec2> readVec2(const Context& ctx, int index, const std::string& from) {
    const auto raw = readAccessor<float>(ctx, index, 2, false, from);
    std::vector<glm::vec2> v(raw.size() / 2);
    for (std::size_t i = 0; i < v.size(); ++i)
        v[i] = {raw[2 * i], raw[2 * i + 1]};
    return v;
}

std::vector<float> readFloats(const Context& ctx, int index, int comps, const std::string& from) {
    return readAccessor<float>(ctx, index, comps, false, from);
}

std::vector<std::uint32_t> readIndices(const Context& ctx, int index, const std::string& from) {
    return readAccessor<std::uint32_t>(ctx, index, 1, true, from);
}

} // namespace specula::gltf_internal
