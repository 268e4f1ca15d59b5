#include "engine/raytrace/embree_scene.h"

#include "engine/core/error.h"
#include "engine/image/sampling.h"

#include <cmath>
#include <string>

#include <embree3/rtcore.h>

namespace specula {

namespace {

struct GeomRecord {
    ecs::Entity entity;
    std::size_t primitiveIndex = 0;
    Primitive primitive; // shares the mesh and material, so they outlive registry edits
    std::vector<glm::vec3> positions; // world space
    std::vector<glm::vec3> normals;   // world space; empty when the mesh has none
    std::vector<std::uint32_t> indices;
    bool mirrored = false; // negative determinant: glTF then treats clockwise as front
};

bool finite(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Carries the caller's entity filter to Embree's context filter callback; the Embree
// context must be the first member so the callback can get back to the whole.
struct FilterContext {
    RTCIntersectContext base;
    const EmbreeScene::Filter* accept;
    const std::vector<GeomRecord>* records;
};

void contextFilter(const RTCFilterFunctionNArguments* args) {
    const auto* ctx = reinterpret_cast<const FilterContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const unsigned geomID = RTCHitN_geomID(args->hit, args->N, i);
        if (!(*ctx->accept)((*ctx->records)[geomID].entity)) args->valid[i] = 0;
    }
}

void embreeError(void* userPtr, RTCError code, const char* str) {
    auto* message = static_cast<std::string*>(userPtr);
    if (message->empty())
        *message = "Embree error " + std::to_string(int(code)) + ": " + (str ? str : "");
}

} // namespace

struct EmbreeScene::Impl {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::vector<GeomRecord> records; // index = Embree geometry id
    std::string error;

    ~Impl() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }

    void check(const char* what) {
        if (!error.empty()) throw Error("", "", std::string(what) + ": " + error);
    }
};

EmbreeScene::EmbreeScene(ecs::Registry& registry, const Filter& include)
    : impl_(std::make_unique<Impl>()) {
    Impl& im = *impl_;
    im.device = rtcNewDevice(nullptr);
    if (!im.device)
        throw Error("", "",
                    "cannot create an Embree device (error " +
                        std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
    rtcSetDeviceErrorFunction(im.device, embreeError, &im.error);
    im.scene = rtcNewScene(im.device);
    rtcSetSceneFlags(im.scene,
                     RTCSceneFlags(RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION));
    im.check("cannot create the Embree scene");

    registry.view<Mesh, Transform>().each([&](ecs::Entity e, Mesh& mesh, Transform& xf) {
        if (include && !include(e)) return;
        const glm::mat3 linear(xf.world);
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(linear));
        const bool mirrored = glm::determinant(linear) < 0.f;
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            const Primitive& prim = mesh.primitives[p];
            if (!prim.mesh) continue;
            const MeshData& md = *prim.mesh;
            const std::size_t nv = md.positions.size();
            const std::size_t nt = md.indices.size() / 3;
            if (nv == 0 || nt == 0) continue;

            GeomRecord rec;
            rec.entity = e;
            rec.primitiveIndex = p;
            rec.primitive = prim;
            rec.mirrored = mirrored;
            rec.positions.reserve(nv);
            for (const glm::vec3& v : md.positions)
                rec.positions.push_back(glm::vec3(xf.world * glm::vec4(v, 1.f)));
            if (md.normals.size() == nv) {
                rec.normals.reserve(nv);
                for (const glm::vec3& n : md.normals)
                    rec.normals.push_back(normalMatrix * n);
            }
            // Out-of-range indices would read past Embree's buffer: make them degenerate.
            rec.indices.assign(md.indices.begin(), md.indices.begin() + std::ptrdiff_t(nt * 3));
            for (std::size_t t = 0; t < nt; ++t) {
                std::uint32_t* tri = &rec.indices[t * 3];
                if (tri[0] >= nv || tri[1] >= nv || tri[2] >= nv) tri[0] = tri[1] = tri[2] = 0;
            }

            RTCGeometry geom = rtcNewGeometry(im.device, RTC_GEOMETRY_TYPE_TRIANGLE);
            auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(
                geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv));
            auto* ib = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
                geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), nt));
            if (!vb || !ib) {
                rtcReleaseGeometry(geom);
                im.check("cannot allocate Embree buffers");
                throw Error("", "", "cannot allocate Embree buffers");
            }
            for (std::size_t i = 0; i < nv; ++i) {
                vb[i * 3 + 0] = rec.positions[i].x;
                vb[i * 3 + 1] = rec.positions[i].y;
                vb[i * 3 + 2] = rec.positions[i].z;
            }
            std::copy(rec.indices.begin(), rec.indices.end(), ib);
            rtcCommitGeometry(geom);
            rtcAttachGeometryByID(im.scene, geom, unsigned(im.records.size()));
            rtcReleaseGeometry(geom);
            im.records.push_back(std::move(rec));
        }
    });
    rtcCommitScene(im.scene);
    im.check("cannot build the Embree scene");
}

EmbreeScene::~EmbreeScene() = default;
EmbreeScene::EmbreeScene(EmbreeScene&&) noexcept = default;
EmbreeScene& EmbreeScene::operator=(EmbreeScene&&) noexcept = default;

std::size_t EmbreeScene::geometryCount() const {
    return impl_ ? impl_->records.size() : 0;
}

std::optional<Hit> EmbreeScene::intersect(glm::vec3 origin, glm::vec3 dir, float tnear, float tfar,
                                          const Filter* accept) const {
    if (!impl_ || impl_->records.empty() || !finite(origin) || !finite(dir) ||
        glm::dot(dir, dir) == 0.f)
        return std::nullopt;

    FilterContext ctx;
    rtcInitIntersectContext(&ctx.base);
    ctx.accept = accept;
    ctx.records = &impl_->records;
    if (accept && *accept) ctx.base.filter = contextFilter;

    RTCRayHit rh{};
    rh.ray.org_x = origin.x;
    rh.ray.org_y = origin.y;
    rh.ray.org_z = origin.z;
    rh.ray.dir_x = dir.x;
    rh.ray.dir_y = dir.y;
    rh.ray.dir_z = dir.z;
    rh.ray.tnear = tnear;
    rh.ray.tfar = tfar;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.flags = 0;
    rh.ray.time = 0.f;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->scene, &ctx.base, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;

    const GeomRecord& rec = impl_->records[rh.hit.geomID];
    Hit h;
    h.t = rh.ray.tfar;
    h.position = origin + h.t * dir;
    h.entity = rec.entity;
    h.primitive = &rec.primitive;
    h.primitiveIndex = rec.primitiveIndex;
    h.triangle = rh.hit.primID;
    const float u = rh.hit.u, v = rh.hit.v, w = 1.f - u - v;
    h.barycentric = {u, v};

    const std::uint32_t* tri = &rec.indices[std::size_t(h.triangle) * 3];
    const glm::vec3 p0 = rec.positions[tri[0]], p1 = rec.positions[tri[1]],
                    p2 = rec.positions[tri[2]];
    glm::vec3 ng = glm::cross(p1 - p0, p2 - p0);
    const float ngLen = glm::length(ng);
    if (ngLen > 0.f && std::isfinite(ngLen))
        ng = (rec.mirrored ? -ng : ng) / ngLen;
    else // a sliver Embree still reported: any normal facing the ray will do
        ng = -glm::normalize(dir);
    h.geometricNormal = ng;

    h.normal = ng;
    if (!rec.normals.empty()) {
        const glm::vec3 n =
            w * rec.normals[tri[0]] + u * rec.normals[tri[1]] + v * rec.normals[tri[2]];
        const float len = glm::length(n);
        if (len > 1e-12f && std::isfinite(len)) h.normal = n / len;
    }

    const MeshData& md = *rec.primitive.mesh;
    if (md.uvs.size() == md.positions.size()) {
        const glm::vec2 uv = w * md.uvs[tri[0]] + u * md.uvs[tri[1]] + v * md.uvs[tri[2]];
        if (std::isfinite(uv.x) && std::isfinite(uv.y)) h.uv = uv;
    }

    h.albedo = glm::vec3(1.f);
    if (const MaterialData* mat = rec.primitive.material.get()) {
        h.albedo = glm::vec3(mat->baseColorFactor);
        if (mat->baseColorTexture && !mat->baseColorTexture->empty())
            h.albedo *= glm::vec3(sampleBilinear(*mat->baseColorTexture, h.uv, Wrap::Repeat));
    }
    return h;
}

} // namespace specula
