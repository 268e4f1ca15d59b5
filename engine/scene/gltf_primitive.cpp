#include "gltf_primitive.h"

#include "engine/math/aabb.h"

#include "engine/scene/gltf_accessors.h"
#include "engine/scene/gltf_draco.h"

#include <numeric>

namespace specula::gltf_internal {

namespace {

// Positions, normals, uvs and indices from the primitive's ordinary accessors.
DecodedAttributes readAttributes(const Context& ctx, const tinygltf::Primitive& prim,
                                 const std::string& field, MeshData& md) {
    DecodedAttributes got;
    auto pos = prim.attributes.find("POSITION");
    if (pos == prim.attributes.end()) ctx.fail(field + ".attributes", "no POSITION");
    md.positions = readVec3(ctx, pos->second, field + ".attributes.POSITION");
    const std::size_t n = md.positions.size();
    if (auto a = prim.attributes.find("NORMAL"); a != prim.attributes.end()) {
        md.normals = readVec3(ctx, a->second, field + ".attributes.NORMAL");
        got.hasNormals = true;
        if (md.normals.size() != n)
            ctx.fail(field + ".attributes.NORMAL", "count differs from POSITION's");
    }
    if (auto a = prim.attributes.find("TEXCOORD_0"); a != prim.attributes.end()) {
        md.uvs = readVec2(ctx, a->second, field + ".attributes.TEXCOORD_0");
        got.hasUvs = true;
        if (md.uvs.size() != n)
            ctx.fail(field + ".attributes.TEXCOORD_0", "count differs from POSITION's");
    }
    if (prim.indices >= 0) {
        md.indices = readIndices(ctx, prim.indices, field + ".indices");
    } else {
        if (n > std::size_t(UINT32_MAX)) ctx.fail(field, "too many vertices");
        md.indices.resize(n);
        std::iota(md.indices.begin(), md.indices.end(), 0u);
    }
    return got;
}

// Positions finite, indices in range; an incomplete last triangle is dropped with a warning.
void checkTriangles(Context& ctx, const std::string& field, MeshData& md) {
    const std::size_t n = md.positions.size();
    for (std::size_t i = 0; i < n; ++i)
        if (!finite(md.positions[i]))
            ctx.fail(field + ".attributes.POSITION",
                     "non-finite position at vertex " + std::to_string(i));
    for (std::size_t k = 0; k < md.indices.size(); ++k)
        if (md.indices[k] >= n)
            ctx.fail(field + ".indices", "index out of range: indices[" + std::to_string(k) +
                                             "] = " + std::to_string(md.indices[k]) + " but only " +
                                             std::to_string(n) + " vertices");
    if (md.indices.size() % 3 != 0) {
        ctx.warn(field, "index count " + std::to_string(md.indices.size()) +
                            " is not a multiple of 3; the incomplete triangle is dropped");
        md.indices.resize(md.indices.size() - md.indices.size() % 3);
    }
}

// Area-weighted vertex normals where the asset gives none, or gives zero/NaN ones:
// the unnormalised face cross product is twice the triangle's area, which is the weight.
std::vector<glm::vec3> areaWeightedNormals(const MeshData& md) {
    std::vector<glm::vec3> generated(md.positions.size(), glm::vec3(0.f));
    for (std::size_t t = 0; t + 2 < md.indices.size(); t += 3) {
        const std::uint32_t a = md.indices[t], b = md.indices[t + 1], c = md.indices[t + 2];
        const glm::vec3 f =
            glm::cross(md.positions[b] - md.positions[a], md.positions[c] - md.positions[a]);
        if (!finite(f)) continue;
        generated[a] += f;
        generated[b] += f;
        generated[c] += f;
    }
    return generated;
}

void repairNormals(MeshData& md, bool hasNormals) {
    const std::size_t n = md.positions.size();
    std::vector<glm::vec3> generated; // computed on the first unusable normal only
    auto usable = [](const glm::vec3& v) {
        const float l = glm::dot(v, v);
        return finite(v) && std::isfinite(l) && l > 1e-24f;
    };
    if (!hasNormals) md.normals.assign(n, glm::vec3(0.f));
    for (std::size_t i = 0; i < n; ++i) {
        glm::vec3 v = md.normals[i];
        if (!usable(v)) {
            if (generated.empty()) generated = areaWeightedNormals(md);
            v = generated[i];
        }
        // A vertex of degenerate triangles only has no defined normal; any unit vector
        // keeps shading finite.
        md.normals[i] = usable(v) ? glm::normalize(v) : glm::vec3(0.f, 1.f, 0.f);
    }
}

void computeBounds(MeshData& md) {
    if (md.positions.empty()) return;
    const Aabb box = Aabb::of(md.positions);
    md.boundsMin = box.min;
    md.boundsMax = box.max;
}

} // namespace

std::shared_ptr<const MeshData> buildPrimitive(Context& ctx, const tinygltf::Primitive& prim,
                                               const std::string& field) {
    auto md = std::make_shared<MeshData>();
    auto draco = prim.extensions.find("KHR_draco_mesh_compression");
    const DecodedAttributes got = draco != prim.extensions.end()
                                      ? decodeDraco(ctx, prim, draco->second, field, *md)
                                      : readAttributes(ctx, prim, field, *md);
    checkTriangles(ctx, field, *md);
    if (got.hasUvs)
        for (auto& uv : md->uvs)
            if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = glm::vec2(0.f);
    if (!got.hasUvs) md->uvs.clear();
    repairNormals(*md, got.hasNormals);
    computeBounds(*md);
    return md;
}

} // namespace specula::gltf_internal
