#include "gltf_convert.h"

#include "engine/math/aabb.h"

#include "engine/scene/components.h"
#include "engine/scene/gltf_animation.h"
#include "engine/scene/gltf_context.h"
#include "engine/scene/gltf_material.h"
#include "engine/scene/gltf_node.h"
#include "engine/scene/gltf_primitive.h"

#include <map>
#include <optional>
#include <set>

namespace specula::gltf_internal {

namespace {

const std::set<std::string>& supportedRequiredExtensions() {
    static const std::set<std::string> s{"KHR_draco_mesh_compression", "KHR_mesh_quantization",
                                         "KHR_materials_unlit"};
    return s;
}

// One node reached from the scene, converted but not yet an entity.
struct NodeDesc {
    int node = -1;
    int parent = -1; // index into the descs vector
    Transform transform;
    const Mesh* mesh = nullptr;
    std::optional<Camera> camera;
};

class SceneConverter {
public:
    SceneConverter(const std::string& file, const tinygltf::Model& model, LoadedScene& out)
        : ctx_(file, model, out.warnings), m_(model), out_(out), materials_(ctx_) {}

    void convert(ecs::Registry& registry) {
        checkAsset();
        out_.extensionsUsed = m_.extensionsUsed;
        const std::vector<NodeDesc> descs = walkHierarchy(rootNodes());
        computeBounds(descs);
        countMaterials();
        const std::map<int, NodeAnimation> animations = readNodeAnimations(ctx_);
        // Only now touch the registry: a failure above leaves it unchanged.
        createEntities(descs, animations, registry);
    }

private:
    void checkAsset() const {
        // glTF 2.x only: a major version this loader does not know may mean anything.
        const std::string& version = m_.asset.version;
        if (version.empty() || version.substr(0, version.find('.')) != "2")
            ctx_.fail("asset.version", "expected a glTF 2.x version, got '" + version + "'");
        if (!m_.asset.minVersion.empty() && m_.asset.minVersion.substr(0, 2) != "2.")
            ctx_.fail("asset.minVersion", "expected 2.x, got '" + m_.asset.minVersion + "'");
        for (const auto& ext : m_.extensionsRequired)
            if (!supportedRequiredExtensions().count(ext))
                ctx_.fail("extensionsRequired", "requires unsupported extension '" + ext + "'");
    }

    // The default scene's roots (or the first scene's), or every node no other node lists
    // as a child when the file has no scenes.
    std::vector<int> rootNodes() const {
        if (!m_.scenes.empty()) {
            const int s = m_.defaultScene >= 0 ? m_.defaultScene : 0;
            return ctx_.at(m_.scenes, s, "scenes", "scene").nodes;
        }
        std::vector<int> roots;
        std::vector<char> isChild(m_.nodes.size(), 0);
        for (std::size_t i = 0; i < m_.nodes.size(); ++i)
            for (int c : m_.nodes[i].children)
                if (c >= 0 && std::size_t(c) < m_.nodes.size()) isChild[std::size_t(c)] = 1;
        for (std::size_t i = 0; i < m_.nodes.size(); ++i)
            if (!isChild[i]) roots.push_back(int(i));
        return roots;
    }

    // Depth-first, parents before children, with an explicit stack so that a deep or
    // cyclic hierarchy in a hostile file cannot overflow the call stack.
    std::vector<NodeDesc> walkHierarchy(const std::vector<int>& roots) {
        std::vector<NodeDesc> descs;
        std::vector<char> seen(m_.nodes.size(), 0);
        std::vector<std::pair<int, int>> stack; // node, parent desc
        for (auto it = roots.rbegin(); it != roots.rend(); ++it)
            stack.emplace_back(*it, -1);
        while (!stack.empty()) {
            const auto [ni, parent] = stack.back();
            stack.pop_back();
            const auto& node =
                ctx_.at(m_.nodes, ni, "nodes",
                        parent < 0 ? std::string("scene.nodes")
                                   : idx("nodes", std::size_t(descs[std::size_t(parent)].node)) +
                                         ".children");
            const std::string nf = idx("nodes", std::size_t(ni));
            if (seen[std::size_t(ni)])
                ctx_.fail(nf, "node reached twice in the hierarchy (shared child or cycle)");
            seen[std::size_t(ni)] = 1;
            descs.push_back(describe(node, ni, parent, descs));
            const int self = int(descs.size() - 1);
            for (auto c = node.children.rbegin(); c != node.children.rend(); ++c)
                stack.emplace_back(*c, self);
        }
        return descs;
    }

    NodeDesc describe(const tinygltf::Node& node, int ni, int parent,
                      const std::vector<NodeDesc>& descs) {
        const std::string nf = idx("nodes", std::size_t(ni));
        NodeDesc d;
        d.node = ni;
        d.parent = parent;
        d.transform = localTransform(ctx_, node, nf);
        d.transform.world = d.transform.local();
        if (parent >= 0)
            d.transform.world = descs[std::size_t(parent)].transform.world * d.transform.world;
        if (node.mesh >= 0)
            d.mesh = &mesh(node.mesh, nf + ".mesh");
        else if (node.mesh < -1)
            ctx_.fail(nf + ".mesh", "negative index");
        if (node.camera >= 0) d.camera = camera(ctx_, node.camera, nf + ".camera");
        return d;
    }

    const Mesh& mesh(int index, const std::string& from) {
        const auto& gm = ctx_.at(m_.meshes, index, "meshes", from);
        if (auto it = meshes_.find(index); it != meshes_.end()) return it->second;
        Mesh mesh;
        mesh.name = gm.name;
        const std::string mf = idx("meshes", std::size_t(index));
        for (std::size_t p = 0; p < gm.primitives.size(); ++p) {
            const auto& prim = gm.primitives[p];
            const std::string pf = mf + ".primitives[" + std::to_string(p) + "]";
            if (prim.mode != TINYGLTF_MODE_TRIANGLES) {
                ctx_.warn(pf, "mode " + std::to_string(prim.mode) +
                                  " skipped; only TRIANGLES (4) is loaded");
                continue;
            }
            Primitive out;
            out.mesh = buildPrimitive(ctx_, prim, pf);
            out.material = materials_.material(prim.material, pf + ".material");
            out_.primitives += 1;
            out_.vertices += out.mesh->positions.size();
            out_.triangles += out.mesh->indices.size() / 3;
            mesh.primitives.push_back(std::move(out));
        }
        out_.meshes += 1;
        return meshes_.emplace(index, std::move(mesh)).first->second;
    }

    // World bounds over every instance; vertices are transformed exactly, not just the
    // corners of the local box, so rotated instances do not inflate the bounds.
    void computeBounds(const std::vector<NodeDesc>& descs) {
        Aabb box;
        for (const auto& d : descs) {
            if (!d.mesh) continue;
            for (const auto& p : d.mesh->primitives)
                for (const auto& v : p.mesh->positions) {
                    const glm::vec3 w = glm::vec3(d.transform.world * glm::vec4(v, 1.f));
                    if (!finite(w)) ctx_.fail("nodes", "world-space bounds are not finite");
                    box.extend(w);
                }
        }
        if (box.empty()) box = Aabb{glm::vec3(0.f), glm::vec3(0.f)}; // no mesh: a point
        out_.boundsMin = box.min;
        out_.boundsMax = box.max;
    }

    void countMaterials() {
        std::set<const MaterialData*> mats;
        for (const auto& [i, mesh] : meshes_)
            for (const auto& p : mesh.primitives)
                mats.insert(p.material.get());
        out_.materials = mats.size();
    }

    void createEntities(const std::vector<NodeDesc>& descs,
                        const std::map<int, NodeAnimation>& animations, ecs::Registry& registry) {
        std::vector<ecs::Entity> entities(descs.size());
        for (std::size_t i = 0; i < descs.size(); ++i) {
            const NodeDesc& d = descs[i];
            const tinygltf::Node& node = m_.nodes[std::size_t(d.node)];
            const ecs::Entity e = registry.create();
            entities[i] = e;
            registry.emplace<Name>(
                e, Name{node.name.empty() ? "node_" + std::to_string(d.node) : node.name});
            Transform t = d.transform;
            t.parent = d.parent >= 0 ? entities[std::size_t(d.parent)] : ecs::kNullEntity;
            registry.emplace<Transform>(e, t);
            registry.emplace<SceneNode>(e, SceneNode{d.node});
            if (d.mesh) registry.emplace<Mesh>(e, *d.mesh);
            if (d.camera) registry.emplace<Camera>(e, *d.camera);
            if (const auto a = animations.find(d.node); a != animations.end())
                registry.emplace<NodeAnimation>(e, a->second);
            if (!node.extras_json_string.empty())
                registry.emplace<Extras>(e, Extras{node.extras_json_string});
            out_.entities.push_back(e);
            if (d.parent < 0) out_.roots.push_back(e);
        }
        out_.nodes = descs.size();
    }

    Context ctx_;
    const tinygltf::Model& m_;
    LoadedScene& out_;
    MaterialCache materials_;
    std::map<int, Mesh> meshes_;
};

} // namespace

void convertScene(const std::string& file, const tinygltf::Model& model, LoadedScene& out,
                  ecs::Registry& registry) {
    SceneConverter(file, model, out).convert(registry);
}

} // namespace specula::gltf_internal
