#include "scene_markup.h"

#include "components/reflection_probe/system/reflector_roughness.h"
#include "engine/core/error.h"
#include "engine/scene/components.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <unordered_map>

namespace specula {

using nlohmann::json;

namespace {

json extrasOf(ecs::Registry& reg, ecs::Entity e, const std::string& file) {
    const Extras* x = reg.find<Extras>(e);
    if (!x || x->json.empty()) return json::object();
    try {
        json j = json::parse(x->json);
        return j.is_object() ? j : json::object();
    } catch (const json::parse_error&) {
        const Name* n = reg.find<Name>(e);
        throw Error(file, "nodes[" + (n ? n->value : "?") + "].extras", "is not valid JSON");
    }
}

std::string nameOf(ecs::Registry& reg, ecs::Entity e) {
    const Name* n = reg.find<Name>(e);
    return n && !n->value.empty() ? n->value : "node" + std::to_string(e.index);
}

} // namespace

SceneMarkup readSceneMarkup(ecs::Registry& reg, const LoadedScene& scene, const std::string& file,
                            const ReflectorRule& rule) {
    std::unordered_map<std::uint32_t, std::vector<ecs::Entity>> children;
    for (ecs::Entity e : scene.entities)
        if (const Transform* t = reg.find<Transform>(e); t && !t->parent.isNull())
            children[t->parent.index].push_back(e);

    auto subtreeMeshes = [&](ecs::Entity root) {
        std::vector<ecs::Entity> out, stack{root};
        while (!stack.empty()) {
            ecs::Entity e = stack.back();
            stack.pop_back();
            if (reg.has<Mesh>(e)) out.push_back(e);
            for (ecs::Entity c : children[e.index])
                stack.push_back(c);
        }
        return out;
    };

    SceneMarkup m;
    std::unordered_set<ecs::Entity> claimed; // entities already a probe or reflector
    std::vector<ecs::Entity> notReflectors;  // nodes marked "specula_reflector": false
    for (ecs::Entity e : scene.entities) {
        const json x = extrasOf(reg, e, file);
        const std::string where = "nodes[" + nameOf(reg, e) + "].extras.";
        if (x.contains("specula_probe")) {
            const json& p = x["specula_probe"];
            if (!p.is_object() && !p.is_boolean())
                throw Error(file, where + "specula_probe", "expected an object or true");
            ProbeMarkup probe;
            probe.node = nameOf(reg, e);
            probe.position = glm::vec3(reg.get<Transform>(e).world[3]);
            probe.options = p.is_object() ? p : json::object();
            // The cell reflectors move in: a side of zero, a negative or a non-number one
            // would size everything after it (reach, light-field slabs) from nonsense.
            if (probe.options.contains("cell_size")) {
                const json& c = probe.options["cell_size"];
                if (!c.is_number() || !std::isfinite(c.get<double>()) || c.get<double>() <= 0.0 ||
                    c.get<double>() > 1e4)
                    throw Error(file, where + "specula_probe.cell_size",
                                "expected a side in metres in (0, 10000], got " + c.dump());
            }
            m.probes.push_back(std::move(probe));
            claimed.insert(e);
        }
        if (x.contains("specula_reflector")) {
            const json& r = x["specula_reflector"];
            ReflectorMarkup refl;
            refl.node = nameOf(reg, e);
            if (r.is_boolean()) {
                if (!r.get<bool>()) {
                    notReflectors.push_back(e);
                    continue;
                }
            } else if (r.is_object()) {
                if (r.contains("f0")) {
                    if (!r["f0"].is_number() || r["f0"].get<double>() < 0.0 ||
                        r["f0"].get<double>() > 1.0)
                        throw Error(file, where + "specula_reflector.f0",
                                    "expected a number in [0, 1]");
                    refl.f0 = r["f0"].get<float>();
                }
                if (r.contains("roughness")) {
                    const json& rough = r["roughness"];
                    if (rough.is_string() && rough.get<std::string>() == "material") {
                        const MaterialRoughness mr = materialRoughness(reg, subtreeMeshes(e));
                        refl.roughness = mr.factor;
                        refl.roughnessMap = mr.map;
                    } else if (!rough.is_number() || rough.get<double>() < 0.0 ||
                               rough.get<double>() > 1.0) {
                        throw Error(file, where + "specula_reflector.roughness",
                                    "expected a number in [0, 1] (GGX, alpha = roughness^2) or "
                                    "\"material\", got " +
                                        rough.dump());
                    } else {
                        refl.roughness = rough.get<float>();
                    }
                }
            } else {
                throw Error(file, where + "specula_reflector", "expected true, false or an object");
            }
            refl.meshes = subtreeMeshes(e);
            for (ecs::Entity me : refl.meshes) {
                m.mirrorEntities.insert(me);
                claimed.insert(me);
            }
            claimed.insert(e);
            m.reflectors.push_back(std::move(refl));
        }
    }

    // Reflectors by material, where the markup says nothing.
    std::unordered_set<ecs::Entity> excluded;
    for (ecs::Entity e : notReflectors)
        for (ecs::Entity me : subtreeMeshes(e))
            excluded.insert(me);
    const auto qualifies = [&](const Primitive& p) {
        return p.material && p.material->metallic() >= rule.minMetallic &&
               p.material->roughness() <= rule.maxRoughness;
    };
    for (ecs::Entity e : scene.entities) {
        const Mesh* mesh = reg.find<Mesh>(e);
        if (!mesh || mesh->primitives.empty() || m.mirrorEntities.count(e) || excluded.count(e))
            continue;
        if (!std::all_of(mesh->primitives.begin(), mesh->primitives.end(), qualifies)) continue;
        float luminance = 0.f;
        for (const Primitive& p : mesh->primitives) {
            const glm::vec4& c = p.material->baseColorFactor;
            luminance += 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
        }
        ReflectorMarkup refl;
        refl.node = nameOf(reg, e);
        refl.meshes = {e};
        refl.f0 = std::clamp(luminance / float(mesh->primitives.size()), 0.f, 1.f);
        const MaterialRoughness mr = materialRoughness(reg, refl.meshes);
        refl.roughness = mr.factor;
        refl.roughnessMap = mr.map;
        m.mirrorEntities.insert(e);
        m.reflectors.push_back(std::move(refl));
    }

    // Environment objects: root subtrees.
    std::vector<ecs::Entity> objectRoots;
    for (ecs::Entity r : scene.roots) {
        // A lone mesh-less root is a wrapper around the whole scene, not one object.
        if (scene.roots.size() == 1 && !reg.has<Mesh>(r) && !children[r.index].empty() &&
            extrasOf(reg, r, file).empty())
            for (ecs::Entity c : children[r.index])
                objectRoots.push_back(c);
        else
            objectRoots.push_back(r);
    }
    std::map<std::string, std::size_t> groups;
    for (ecs::Entity r : objectRoots) {
        if (claimed.count(r)) continue;
        std::vector<ecs::Entity> meshes;
        for (ecs::Entity me : subtreeMeshes(r))
            if (!m.mirrorEntities.count(me)) meshes.push_back(me);
        if (meshes.empty()) continue;
        std::string name = nameOf(reg, r);
        const json x = extrasOf(reg, r, file);
        if (x.contains("specula_layer")) {
            if (!x["specula_layer"].is_string())
                throw Error(file, "nodes[" + name + "].extras.specula_layer", "expected a string");
            name = x["specula_layer"].get<std::string>();
        }
        auto [it, fresh] = groups.emplace(name, m.objects.size());
        if (fresh) {
            EnvironmentObject o;
            o.name = name;
            m.objects.push_back(std::move(o));
        }
        EnvironmentObject& o = m.objects[it->second];
        for (ecs::Entity me : meshes) {
            o.meshes.push_back(me);
            o.bounds.extend(meshWorldBounds(reg, me));
        }
    }
    return m;
}

glm::vec3 markupProbeCentre(const ecs::Registry& reg, const SceneMarkup& m,
                            const LoadedScene& scene) {
    if (!m.probes.empty()) return m.probes.front().position;
    if (!m.mirrorEntities.empty()) {
        Aabb mirrors;
        for (ecs::Entity e : m.mirrorEntities)
            mirrors.extend(meshWorldBounds(reg, e));
        return mirrors.centre();
    }
    return 0.5f * (scene.boundsMin + scene.boundsMax);
}

float markupCellSize(const SceneMarkup& m) {
    if (!m.probes.empty()) {
        const json& o = m.probes.front().options;
        if (o.contains("cell_size") && o["cell_size"].is_number() &&
            o["cell_size"].get<double>() > 0.0)
            return o["cell_size"].get<float>();
    }
    return 1.5f;
}

float markupReflectorReach(const ecs::Registry& reg, const SceneMarkup& m, glm::vec3 centre,
                           float cellSize) {
    float reach = 0.5f * std::sqrt(3.f) * cellSize;
    for (ecs::Entity e : m.mirrorEntities) {
        const Aabb b = meshWorldBounds(reg, e);
        if (b.empty()) continue;
        // The box corner farthest from the centre, per axis the farther face.
        const glm::vec3 far = glm::max(glm::abs(b.min - centre), glm::abs(b.max - centre));
        reach = std::max(reach, glm::length(far));
    }
    return reach;
}

} // namespace specula
