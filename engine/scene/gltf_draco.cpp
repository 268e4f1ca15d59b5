#include "gltf_draco.h"

#include "engine/scene/gltf_accessors.h"

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>

#include <memory>
#include <type_traits>

namespace specula::gltf_internal {

namespace {

// The payload in bufferView `view` as a triangle mesh; `ef` names the extension object.
std::unique_ptr<draco::Mesh> decodePayload(const Context& ctx, int view, const std::string& ef) {
    const Bytes bytes = viewBytes(ctx, view, ef);
    if (bytes.size == 0) ctx.fail(ef, "undecodable Draco payload: empty bufferView");
    const std::string undecodable =
        "undecodable Draco payload in " + idx("bufferViews", std::size_t(view)) + ": ";
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(bytes.data), bytes.size);
    std::unique_ptr<draco::Mesh> mesh;
    try {
        auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
        if (!type.ok()) ctx.fail(ef, undecodable + oneLine(type.status().error_msg_string()));
        if (type.value() != draco::TRIANGULAR_MESH)
            ctx.fail(ef, undecodable + "not a triangle mesh");
        draco::Decoder decoder;
        auto result = decoder.DecodeMeshFromBuffer(&buffer);
        if (!result.ok()) ctx.fail(ef, undecodable + oneLine(result.status().error_msg_string()));
        mesh = std::move(result).value();
    } catch (const std::bad_alloc&) {
        ctx.fail(ef, undecodable + "decoder ran out of memory");
    }
    if (!mesh) ctx.fail(ef, "undecodable Draco payload: decoder returned no mesh");
    return mesh;
}

// One attribute of the decoded primitive, wherever it comes from.
class AttributeReader {
public:
    AttributeReader(Context& ctx, const tinygltf::Primitive& prim, const tinygltf::Value& attrs,
                    const draco::Mesh& mesh, const std::string& field)
        : ctx_(ctx), prim_(prim), attrs_(attrs), mesh_(mesh), field_(field),
          ef_(field + ".extensions.KHR_draco_mesh_compression"), points_(mesh.num_points()) {}

    // False when neither the payload nor the primitive has the attribute.
    template <typename Vec> bool read(const char* name, std::vector<Vec>& dst) {
        const tinygltf::Value& id = attrs_.Get(name);
        if (!id.IsInt()) return readAccessor(name, dst);
        readPayload(name, id.Get<int>(), dst);
        warnOnCountMismatch(name);
        return true;
    }

private:
    // Attributes outside the extension come from ordinary accessors.
    template <typename Vec> bool readAccessor(const char* name, std::vector<Vec>& dst) {
        auto a = prim_.attributes.find(name);
        if (a == prim_.attributes.end()) return false;
        const std::string af = field_ + ".attributes." + name;
        if constexpr (std::is_same_v<Vec, glm::vec3>)
            dst = readVec3(ctx_, a->second, af);
        else
            dst = readVec2(ctx_, a->second, af);
        if (dst.size() != points_)
            ctx_.fail(af, "count " + std::to_string(dst.size()) + " differs from the " +
                              std::to_string(points_) + " Draco points");
        return true;
    }

    template <typename Vec> void readPayload(const char* name, int id, std::vector<Vec>& dst) {
        constexpr int comps = Vec::length();
        const std::string af = ef_ + ".attributes." + name;
        const draco::PointAttribute* pa = mesh_.GetAttributeByUniqueId(std::uint32_t(id));
        if (!pa)
            ctx_.fail(af, "undecodable Draco payload: attribute id " + std::to_string(id) +
                              " is not in the payload");
        if (pa->num_components() != comps)
            ctx_.fail(af, "Draco attribute has " + std::to_string(int(pa->num_components())) +
                              " components, expected " + std::to_string(comps));
        dst.resize(points_);
        float tmp[4] = {0, 0, 0, 0};
        for (std::size_t i = 0; i < points_; ++i) {
            const draco::AttributeValueIndex vi =
                pa->mapped_index(draco::PointIndex(std::uint32_t(i)));
            if (vi.value() >= pa->size() || !pa->ConvertValue<float>(vi, std::int8_t(comps), tmp))
                ctx_.fail(af, "undecodable Draco payload: point " + std::to_string(i) +
                                  " maps to no attribute value");
            for (int c = 0; c < comps; ++c)
                dst[i][c] = tmp[c];
        }
    }

    // glTF says the accessor describes the decoded data; a disagreement is worth a note.
    void warnOnCountMismatch(const char* name) {
        const auto& accessors = ctx_.model().accessors;
        auto a = prim_.attributes.find(name);
        if (a != prim_.attributes.end() && a->second >= 0 &&
            std::size_t(a->second) < accessors.size() &&
            accessors[std::size_t(a->second)].count != points_)
            ctx_.warn(ef_, std::string(name) + " accessor count " +
                               std::to_string(accessors[std::size_t(a->second)].count) +
                               " differs from the " + std::to_string(points_) + " decoded points");
    }

    Context& ctx_;
    const tinygltf::Primitive& prim_;
    const tinygltf::Value& attrs_;
    const draco::Mesh& mesh_;
    const std::string& field_;
    const std::string ef_;
    const std::size_t points_;
};

} // namespace

DecodedAttributes decodeDraco(Context& ctx, const tinygltf::Primitive& prim,
                              const tinygltf::Value& ext, const std::string& field, MeshData& md) {
    const std::string ef = field + ".extensions.KHR_draco_mesh_compression";
    if (!ext.IsObject()) ctx.fail(ef, "expected an object");
    const tinygltf::Value& bvv = ext.Get("bufferView");
    const tinygltf::Value& attrs = ext.Get("attributes");
    if (!bvv.IsInt()) ctx.fail(ef + ".bufferView", "expected an integer");
    if (!attrs.IsObject()) ctx.fail(ef + ".attributes", "expected an object");
    const std::unique_ptr<draco::Mesh> mesh = decodePayload(ctx, bvv.Get<int>(), ef);

    AttributeReader reader(ctx, prim, attrs, *mesh, field);
    if (!reader.read("POSITION", md.positions)) ctx.fail(field + ".attributes", "no POSITION");
    DecodedAttributes decoded;
    decoded.hasNormals = reader.read("NORMAL", md.normals);
    decoded.hasUvs = reader.read("TEXCOORD_0", md.uvs);

    md.indices.resize(std::size_t(mesh->num_faces()) * 3);
    for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f) {
        const auto& face = mesh->face(f);
        for (int k = 0; k < 3; ++k)
            md.indices[std::size_t(f.value()) * 3 + std::size_t(k)] = face[k].value();
    }
    return decoded;
}

} // namespace specula::gltf_internal
