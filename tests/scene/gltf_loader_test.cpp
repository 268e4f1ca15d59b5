// The glTF loader on the shared test scenes and the bundled room: the counts the files
// declare, Draco against the plain box, the node hierarchy's world matrices, textures as
// linear float RGBA, the room's named nodes and markup, normals generated where missing. Bad
// files refused: gltf_loader_errors_test.cpp.
#include "engine/ecs/registry.h"
#include "engine/scene/components.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/transform_system.h"
#include "gltf_loader_fixture.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <glm/gtc/matrix_inverse.hpp>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace specula;

namespace {

using test::gltf_files::gltfJson;
using test::gltf_files::kRoom;
using test::gltf_files::kScenes;
using test::gltf_files::TempDir;

struct Counts {
    std::size_t meshes = 0, primitives = 0, vertices = 0, triangles = 0;
};

// Counts as the file's accessors declare them: each mesh a node uses, once; POSITION count
// for vertices, indices count / 3 for triangles.
Counts countsFromAccessors(const nlohmann::json& j) {
    std::set<int> used;
    for (const auto& n : j["nodes"])
        if (n.contains("mesh")) used.insert(n["mesh"].get<int>());
    Counts c;
    for (int m : used) {
        ++c.meshes;
        for (const auto& p : j["meshes"][std::size_t(m)]["primitives"]) {
            if (p.value("mode", 4) != 4) continue;
            ++c.primitives;
            const auto verts =
                j["accessors"][p["attributes"]["POSITION"].get<std::size_t>()]["count"]
                    .get<std::size_t>();
            c.vertices += verts;
            c.triangles +=
                p.contains("indices")
                    ? j["accessors"][p["indices"].get<std::size_t>()]["count"].get<std::size_t>() /
                          3
                    : verts / 3;
        }
    }
    return c;
}

ecs::Entity byName(ecs::Registry& reg, const LoadedScene& s, const std::string& name) {
    for (ecs::Entity e : s.entities)
        if (reg.get<Name>(e).value == name) return e;
    return ecs::kNullEntity;
}

} // namespace

class SharedScenes : public ::testing::TestWithParam<const char*> {};

TEST_P(SharedScenes, LoadsWithTheCountsTheFileDefines) {
    const fs::path path = kScenes / GetParam();
    ecs::Registry reg;
    const LoadedScene s = loadGltf(path.string(), reg);
    const Counts want = countsFromAccessors(gltfJson(path));
    EXPECT_EQ(s.meshes, want.meshes);
    EXPECT_EQ(s.primitives, want.primitives);
    EXPECT_EQ(s.vertices, want.vertices);
    EXPECT_EQ(s.triangles, want.triangles);
    EXPECT_EQ(s.entities.size(), s.nodes);
    EXPECT_FALSE(s.roots.empty());
    for (int a = 0; a < 3; ++a)
        EXPECT_LT(s.boundsMin[a], s.boundsMax[a]);
    // Every vertex normal is unit length and every index addresses a vertex.
    reg.view<Mesh>().each([&](ecs::Entity, Mesh& m) {
        for (const Primitive& p : m.primitives) {
            ASSERT_TRUE(p.mesh && p.material);
            EXPECT_EQ(p.mesh->normals.size(), p.mesh->positions.size());
            for (const auto& n : p.mesh->normals)
                EXPECT_NEAR(glm::length(n), 1.f, 1e-4f);
            for (auto i : p.mesh->indices)
                EXPECT_LT(i, p.mesh->positions.size());
        }
    });
}

INSTANTIATE_TEST_SUITE_P(TestScenes, SharedScenes,
                         ::testing::Values("box/Box.gltf", "box/Box.glb", "box/Box_Draco.glb",
                                           "box-draco-sep/BoxMetaDraco.gltf", "duck/Duck.glb",
                                           "milk-truck/CesiumMilkTruck.gltf"));

// Known numbers, stated so a regression in the independent count above cannot hide one in
// the loader. From the files' accessors: Box 24 vertices / 36 indices; BoxMetaDraco 36 / 36;
// Duck 2399 / 12636; the milk truck's two meshes 2978 vertices / 2856 triangles together.
TEST(GltfLoader, KnownCounts) {
    struct Known {
        const char* file;
        std::size_t vertices, triangles;
    };
    for (const Known& k :
         {Known{"box/Box.glb", 24, 12}, Known{"box/Box.gltf", 24, 12},
          Known{"box/Box_Draco.glb", 24, 12}, Known{"box-draco-sep/BoxMetaDraco.gltf", 36, 12},
          Known{"duck/Duck.glb", 2399, 4212},
          Known{"milk-truck/CesiumMilkTruck.gltf", 2978, 2856}}) {
        ecs::Registry reg;
        const LoadedScene s = loadGltf((kScenes / k.file).string(), reg);
        EXPECT_EQ(s.vertices, k.vertices) << k.file;
        EXPECT_EQ(s.triangles, k.triangles) << k.file;
    }
}

TEST(GltfLoader, DracoBoxHasTheSameTrianglesAsTheUncompressedBox) {
    auto triangles = [](const std::string& file) {
        ecs::Registry reg;
        const LoadedScene s = loadGltf((kScenes / file).string(), reg);
        std::vector<std::array<glm::vec3, 3>> tris;
        reg.view<Mesh, Transform>().each([&](ecs::Entity, Mesh& m, Transform& t) {
            for (const Primitive& p : m.primitives)
                for (std::size_t i = 0; i + 2 < p.mesh->indices.size(); i += 3) {
                    std::array<glm::vec3, 3> tri;
                    for (int k = 0; k < 3; ++k)
                        tri[std::size_t(k)] = glm::vec3(
                            t.world *
                            glm::vec4(p.mesh->positions[p.mesh->indices[i + std::size_t(k)]], 1.f));
                    tris.push_back(tri);
                }
        });
        return tris;
    };
    const auto plain = triangles("box/Box.glb");
    const auto draco = triangles("box/Box_Draco.glb");
    ASSERT_EQ(plain.size(), draco.size());
    // Same triangle set up to vertex order and rotation of each triangle's corners; Draco
    // quantises positions (14 bits over the 1 m box: ~6e-5 m), hence the tolerance.
    const float tol = 1e-3f;
    auto same = [&](const std::array<glm::vec3, 3>& a, const std::array<glm::vec3, 3>& b) {
        for (int r = 0; r < 3; ++r) {
            bool all = true;
            for (int k = 0; k < 3; ++k)
                all = all && glm::length(a[std::size_t(k)] - b[std::size_t((k + r) % 3)]) < tol;
            if (all) return true;
        }
        return false;
    };
    std::vector<bool> used(draco.size(), false);
    for (const auto& t : plain) {
        bool found = false;
        for (std::size_t i = 0; i < draco.size() && !found; ++i)
            if (!used[i] && same(t, draco[i])) used[i] = found = true;
        EXPECT_TRUE(found) << "triangle of Box.glb missing from Box_Draco.glb";
    }
}

TEST(GltfLoader, ChildWorldIsParentTimesLocal) {
    for (const char* file : {"box/Box.gltf", "milk-truck/CesiumMilkTruck.gltf"}) {
        ecs::Registry reg;
        const LoadedScene s = loadGltf((kScenes / file).string(), reg);
        int children = 0;
        for (ecs::Entity e : s.entities) {
            const Transform& t = reg.get<Transform>(e);
            if (t.parent.isNull()) {
                EXPECT_EQ(t.world, t.local());
                continue;
            }
            ++children;
            const glm::mat4 expect = reg.get<Transform>(t.parent).world * t.local();
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r)
                    EXPECT_NEAR(t.world[c][r], expect[c][r], 1e-5f) << file;
        }
        EXPECT_GT(children, 0) << file;
        // The loader's world matrices agree with the engine's transform system.
        std::vector<glm::mat4> before;
        for (ecs::Entity e : s.entities)
            before.push_back(reg.get<Transform>(e).world);
        updateWorldTransforms(reg);
        for (std::size_t i = 0; i < s.entities.size(); ++i)
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r)
                    EXPECT_NEAR(reg.get<Transform>(s.entities[i]).world[c][r], before[i][c][r],
                                1e-5f);
    }
    // Box.gltf: its root's matrix translates the box by 2 along z.
    ecs::Registry reg;
    const LoadedScene s = loadGltf((kScenes / "box/Box.gltf").string(), reg);
    EXPECT_NEAR(s.boundsMin.z, 1.5f, 1e-5f);
    EXPECT_NEAR(s.boundsMax.z, 2.5f, 1e-5f);
}

TEST(GltfLoader, TexturesAreLinearFloatRgba) {
    ecs::Registry reg;
    loadGltf((kScenes / "duck/Duck.glb").string(), reg);
    int textured = 0;
    reg.view<Mesh>().each([&](ecs::Entity, Mesh& m) {
        for (const Primitive& p : m.primitives) {
            if (!p.material->baseColorTexture) continue;
            ++textured;
            const Image& img = *p.material->baseColorTexture;
            EXPECT_EQ(img.channels, 4);
            EXPECT_GT(img.width, 0);
            for (float v : img.pixels)
                ASSERT_TRUE(v >= 0.f && v <= 1.f);
            EXPECT_FALSE(p.mesh->uvs.empty());
        }
    });
    EXPECT_EQ(textured, 1);
}

TEST(DefaultRoom, LoadsWithNamedNodesAndMarkup) {
    ecs::Registry reg;
    const LoadedScene s = loadGltf(kRoom.string(), reg);
    for (const char* name :
         {"floor", "wall_north", "wall_south", "wall_east", "wall_west", "column_red",
          "column_green", "column_blue", "column_yellow", "panel_stripes", "panel_grid",
          "panel_tiles", "table", "table_top", "table_leg_0", "sphere", "torus", "probe", "camera"})
        EXPECT_FALSE(byName(reg, s, name).isNull()) << name;

    EXPECT_NEAR(s.boundsMin.x, -4.f, 1e-4f);
    EXPECT_NEAR(s.boundsMax.x, 4.f, 1e-4f);
    EXPECT_NEAR(s.boundsMin.y, 0.f, 1e-4f);
    EXPECT_NEAR(s.boundsMax.y, 4.f, 1e-4f);
    EXPECT_NEAR(s.boundsMin.z, -4.f, 1e-4f);
    EXPECT_NEAR(s.boundsMax.z, 4.f, 1e-4f);

    const ecs::Entity probe = byName(reg, s, "probe");
    const auto probeJson = nlohmann::json::parse(reg.get<Extras>(probe).json);
    EXPECT_DOUBLE_EQ(probeJson["specula_probe"]["cell_size"].get<double>(), 2.0);
    const glm::vec3 probePos(reg.get<Transform>(probe).world[3]);
    EXPECT_NEAR(probePos.y, 1.2f, 1e-5f);

    const auto sphereJson = nlohmann::json::parse(reg.get<Extras>(byName(reg, s, "sphere")).json);
    EXPECT_DOUBLE_EQ(sphereJson["specula_reflector"]["f0"].get<double>(), 1.0);
    const auto torusJson = nlohmann::json::parse(reg.get<Extras>(byName(reg, s, "torus")).json);
    EXPECT_EQ(torusJson["specula_reflector"], true);

    // Reflectors sit within 0.7 m of the probe; no geometry contains the probe centre.
    for (const char* name : {"sphere", "torus"}) {
        const ecs::Entity e = byName(reg, s, name);
        EXPECT_LT(glm::length(glm::vec3(reg.get<Transform>(e).world[3]) - probePos), 0.7f);
    }
    reg.view<Mesh, Transform>().each([&](ecs::Entity, Mesh& m, Transform& t) {
        const glm::vec3 local = glm::vec3(glm::inverse(t.world) * glm::vec4(probePos, 1.f));
        for (const Primitive& p : m.primitives) {
            const bool inside = glm::all(glm::greaterThan(local, p.mesh->boundsMin)) &&
                                glm::all(glm::lessThan(local, p.mesh->boundsMax));
            EXPECT_FALSE(inside) << m.name << " contains the probe centre";
        }
    });

    // Walls face into the room.
    for (const char* name : {"wall_north", "wall_south", "wall_east", "wall_west", "floor"}) {
        const ecs::Entity e = byName(reg, s, name);
        const Transform& t = reg.get<Transform>(e);
        const auto& mesh = *reg.get<Mesh>(e).primitives.at(0).mesh;
        const glm::vec3 n =
            glm::normalize(glm::inverseTranspose(glm::mat3(t.world)) * mesh.normals[0]);
        const glm::vec3 toCentre = glm::vec3(0.f, 2.f, 0.f) - glm::vec3(t.world[3]);
        EXPECT_GT(glm::dot(n, toCentre), 0.f) << name;
    }

    // The table is a hierarchy, and instanced meshes and shared materials share storage.
    const ecs::Entity table = byName(reg, s, "table");
    EXPECT_EQ(reg.get<Transform>(byName(reg, s, "table_top")).parent, table);
    const auto& leg0 = reg.get<Mesh>(byName(reg, s, "table_leg_0")).primitives.at(0);
    const auto& leg1 = reg.get<Mesh>(byName(reg, s, "table_leg_1")).primitives.at(0);
    EXPECT_EQ(leg0.mesh.get(), leg1.mesh.get());
    EXPECT_EQ(reg.get<Mesh>(byName(reg, s, "sphere")).primitives.at(0).material.get(),
              reg.get<Mesh>(byName(reg, s, "torus")).primitives.at(0).material.get());

    const ecs::Entity cam = byName(reg, s, "camera");
    ASSERT_NE(reg.find<Camera>(cam), nullptr);
    const glm::vec3 eye(reg.get<Transform>(cam).world[3]);
    EXPECT_NEAR(glm::length(eye - probePos), 3.5f, 0.2f);
    const glm::vec3 forward = -glm::vec3(reg.get<Transform>(cam).world[2]);
    EXPECT_GT(glm::dot(glm::normalize(forward), glm::normalize(probePos - eye)), 0.999f);

    // The sphere has smooth normals: each is its position's direction.
    const auto& sphere = *reg.get<Mesh>(byName(reg, s, "sphere")).primitives.at(0).mesh;
    EXPECT_GT(sphere.indices.size() / 3, 1500u);
    for (std::size_t i = 0; i < sphere.positions.size(); ++i)
        EXPECT_GT(glm::dot(sphere.normals[i], glm::normalize(sphere.positions[i])), 0.999f);
}

TEST(GltfLoader, GeneratesAndRepairsNormals) {
    TempDir dir;
    auto j = gltfJson(kScenes / "box/Box.gltf");
    fs::copy_file(kScenes / "box/Box0.bin", dir.path() / "Box0.bin");
    j["meshes"][0]["primitives"][0]["attributes"].erase("NORMAL");
    const fs::path path = dir.path() / "NoNormals.gltf";
    std::ofstream(path) << j.dump();
    ecs::Registry reg;
    loadGltf(path.string(), reg);
    reg.view<Mesh>().each([&](ecs::Entity, Mesh& m) {
        const MeshData& md = *m.primitives.at(0).mesh;
        ASSERT_EQ(md.normals.size(), md.positions.size());
        // Box vertices are not shared between faces, so each normal is its face's normal:
        // along one axis, pointing away from the box centre.
        for (std::size_t i = 0; i < md.normals.size(); ++i) {
            EXPECT_NEAR(glm::length(md.normals[i]), 1.f, 1e-5f);
            EXPECT_NEAR(std::max({std::abs(md.normals[i].x), std::abs(md.normals[i].y),
                                  std::abs(md.normals[i].z)}),
                        1.f, 1e-5f);
            EXPECT_GT(glm::dot(md.normals[i], md.positions[i]), 0.f);
        }
    });
}
