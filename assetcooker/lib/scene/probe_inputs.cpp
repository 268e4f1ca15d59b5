#include "assetcooker/lib/scene/probe_inputs.h"

#include "components/reflection_probe/manifest_fields.h"
#include "engine/raytrace/embree_scene.h"
#include "engine/scene/components.h"
#include "engine/scene/mesh_bounds.h"

#include <map>
#include <sstream>

namespace specula {

namespace {

template <class T> std::string checksumOf(const std::vector<T>& v) {
    return bytesChecksum(v.data(), v.size() * sizeof(T));
}

// One mesh in world space with its materials, as text of checksums.
std::string meshKey(const ecs::Registry& reg, ecs::Entity e) {
    std::ostringstream key;
    const Mesh& mesh = *reg.find<Mesh>(e);
    const glm::mat4& world = reg.find<Transform>(e)->world;
    key << mesh.name << ' ' << bytesChecksum(&world, sizeof world);
    for (const Primitive& p : mesh.primitives) {
        if (p.mesh)
            key << ' ' << checksumOf(p.mesh->positions) << checksumOf(p.mesh->normals)
                << checksumOf(p.mesh->uvs) << checksumOf(p.mesh->indices);
        if (const MaterialData* m = p.material.get()) {
            const float factors[] = {
                m->baseColorFactor.r,      m->baseColorFactor.g, m->baseColorFactor.b,
                m->baseColorFactor.a,      m->metallic(),        m->roughness(),
                m->doubleSided ? 1.f : 0.f};
            key << ' ' << bytesChecksum(factors, sizeof factors);
            if (m->baseColorTexture) key << checksumOf(m->baseColorTexture->pixels);
            if (m->metallicRoughnessTexture) key << checksumOf(m->metallicRoughnessTexture->pixels);
        }
    }
    return key.str();
}

// The inputs of `within` (meshes by entity index: a deterministic order) and every reflector's
// markup, `options` as given, and the sky's bytes.
ProbeInputs inputsOf(const ProbeScene& scene, const std::map<std::uint32_t, ecs::Entity>& within,
                     const std::string& options) {
    std::string geometry;
    for (const auto& [index, e] : within)
        geometry += meshKey(scene.registry, e) + '\n';
    // The reflectors' markup decides what the bake makes too (Fresnel in the plan, the glossy
    // chain under --glossy auto), whatever their materials say.
    for (const ReflectorMarkup& r : scene.markup.reflectors) {
        const float figures[] = {r.f0, r.roughness};
        geometry += r.node + ' ' + bytesChecksum(figures, sizeof figures);
        if (r.roughnessMap) geometry += ' ' + checksumOf(r.roughnessMap->pixels);
        geometry += '\n';
    }
    return {bytesChecksum(geometry.data(), geometry.size()),
            bytesChecksum(options.data(), options.size()), skyChecksum(scene.skyPath)};
}

} // namespace

ProbeInputs levelProbeInputs(ProbeScene& scene, const EmbreeScene& env, const ProbeVolume& probe,
                             const std::string& options) {
    const ecs::Registry& reg = scene.registry;
    std::map<std::uint32_t, ecs::Entity> within; // by index: a deterministic order
    for (ecs::Entity e : scene.markup.mirrorEntities)
        within.emplace(e.index, e);
    for (ecs::Entity e : scene.loaded.entities)
        if (reg.has<Mesh>(e) && reg.has<Transform>(e) &&
            meshWorldBounds(reg, e).overlaps(probe.proxy))
            within.emplace(e.index, e);
    constexpr int kSide = 32;
    for (int axis = 0; axis < 3; ++axis)
        for (float sign : {-1.f, 1.f})
            for (int i = 0; i < kSide; ++i)
                for (int j = 0; j < kSide; ++j) {
                    glm::vec3 d(0.f);
                    d[axis] = sign;
                    d[(axis + 1) % 3] = 2.f * (float(i) + 0.5f) / kSide - 1.f;
                    d[(axis + 2) % 3] = 2.f * (float(j) + 0.5f) / kSide - 1.f;
                    if (const std::optional<Hit> hit = env.intersect(probe.position, d))
                        within.emplace(hit->entity.index, hit->entity);
                }
    return inputsOf(scene, within, options + '\n' + toJson(probe).dump());
}

std::string skyChecksum(const std::string& skyPath) {
    return skyPath.empty() ? "none" : fileChecksum(skyPath);
}

ProbeInputs sceneProbeInputs(const ProbeScene& scene, const std::string& options) {
    const ecs::Registry& reg = scene.registry;
    std::map<std::uint32_t, ecs::Entity> every;
    for (ecs::Entity e : scene.markup.mirrorEntities)
        every.emplace(e.index, e);
    for (ecs::Entity e : scene.loaded.entities)
        if (reg.has<Mesh>(e) && reg.has<Transform>(e)) every.emplace(e.index, e);
    return inputsOf(scene, every, options);
}

} // namespace specula
