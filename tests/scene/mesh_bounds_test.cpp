// Mesh bounds through Transform::world, and the per-frame "reflector outside the
// light-field cell" check built on them (ReflectionProbeSystem::checkCell: the conservative
// world bounds' overhang out of the cell cube), on closed-form positions.
#include "engine/ecs/registry.h"
#include "engine/scene/mesh_bounds.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include <glm/gtc/matrix_transform.hpp>

using namespace specula;

namespace {

// The six axis points at +-0.5: local bounds are the unit cube, but under a 45-degree turn
// about Y the points reach only 0.5 / sqrt(2) along X and Z while the cube's corners reach
// 0.5 sqrt(2): the gap between exact and conservative world bounds, in closed form.
std::shared_ptr<MeshData> octahedron() {
    auto m = std::make_shared<MeshData>();
    m->positions = {{0.5f, 0, 0},  {-0.5f, 0, 0}, {0, 0.5f, 0},
                    {0, -0.5f, 0}, {0, 0, 0.5f},  {0, 0, -0.5f}};
    m->indices = {0, 2, 4, 1, 4, 2, 0, 5, 2, 1, 2, 5, 0, 4, 3, 1, 3, 4, 0, 3, 5, 1, 5, 3};
    return m;
}

ecs::Entity addMesh(ecs::Registry& reg, std::shared_ptr<const MeshData> data, glm::mat4 world) {
    const ecs::Entity e = reg.create();
    Mesh mesh;
    mesh.primitives.push_back(Primitive{std::move(data), std::make_shared<MaterialData>()});
    reg.emplace<Mesh>(e, std::move(mesh));
    Transform t;
    t.world = world;
    reg.emplace<Transform>(e, t);
    return e;
}

glm::mat4 turnedAt(glm::vec3 at) {
    return glm::translate(glm::mat4(1.f), at) *
           glm::rotate(glm::mat4(1.f), glm::radians(45.f), glm::vec3(0, 1, 0));
}

const float kR = 0.5f / std::sqrt(2.f); // an axis point's reach after the turn
const float kC = 0.5f * std::sqrt(2.f); // a cube corner's reach after the turn

// What checkCell computes: > 0 reports the reflector as outside the cell.
float cellOverhang(const ecs::Registry& reg, ecs::Entity reflector, glm::vec3 cellCentre,
                   float halfCell) {
    return meshWorldBoundsConservative(reg, reflector).overhang(Aabb::cube(cellCentre, halfCell));
}

} // namespace

TEST(MeshBounds, StoredLocalBoundsWinOverPositions) {
    auto m = octahedron();
    // Built by hand without bounds: they come from the positions.
    EXPECT_EQ(localBounds(*m).min, glm::vec3(-0.5f));
    EXPECT_EQ(localBounds(*m).max, glm::vec3(0.5f));
    // Stored (as the glTF loader does): used as they are, positions not read.
    m->boundsMin = glm::vec3(-2.f);
    m->boundsMax = glm::vec3(1.f);
    EXPECT_EQ(localBounds(*m).min, glm::vec3(-2.f));
    EXPECT_EQ(localBounds(*m).max, glm::vec3(1.f));
    EXPECT_TRUE(localBounds(MeshData{}).empty());
}

TEST(MeshBounds, ExactAndConservativeWorldBoundsOfATurnedMesh) {
    ecs::Registry reg;
    const glm::vec3 at(1.f, 2.f, 3.f);
    const ecs::Entity e = addMesh(reg, octahedron(), turnedAt(at));
    const Aabb exact = meshWorldBounds(reg, e);
    const Aabb box = meshWorldBoundsConservative(reg, e);
    for (int k = 0; k < 3; ++k) {
        const float exactReach = k == 1 ? 0.5f : kR, boxReach = k == 1 ? 0.5f : kC;
        EXPECT_NEAR(exact.min[k], at[k] - exactReach, 1e-6f) << k;
        EXPECT_NEAR(exact.max[k], at[k] + exactReach, 1e-6f) << k;
        EXPECT_NEAR(box.min[k], at[k] - boxReach, 1e-6f) << k;
        EXPECT_NEAR(box.max[k], at[k] + boxReach, 1e-6f) << k;
    }
    EXPECT_TRUE(box.contains(exact));
    // No Mesh or no Transform: no bounds.
    const ecs::Entity bare = reg.create();
    EXPECT_TRUE(meshWorldBounds(reg, bare).empty());
    EXPECT_TRUE(meshWorldBoundsConservative(reg, bare).empty());
}

TEST(MeshBounds, CellCheckPassesAReflectorInsideAndFlagsOneOutside) {
    ecs::Registry reg;
    const glm::vec3 cell(0.f, 1.f, 0.f);
    const float half = 0.75f; // the default 1.5 m cell
    // Centred: the turned box reaches kC = 0.707 m < 0.75 m on X and Z, 0.5 m on Y.
    const ecs::Entity inside = addMesh(reg, octahedron(), turnedAt(cell));
    EXPECT_NEAR(cellOverhang(reg, inside, cell, half), kC - half, 1e-6f);
    EXPECT_LT(cellOverhang(reg, inside, cell, half), 0.f);
    // 0.3 m along -Z: the geometry itself reaches 0.3 + 0.354 = 0.654 m, inside, but its box
    // 1.007 m: conservative, it is reported (early, never late).
    const ecs::Entity early = addMesh(reg, octahedron(), turnedAt(cell + glm::vec3(0, 0, -0.3f)));
    EXPECT_LT(meshWorldBounds(reg, early).overhang(Aabb::cube(cell, half)), 0.f);
    EXPECT_NEAR(cellOverhang(reg, early, cell, half), 0.3f + kC - half, 1e-6f);
    // 0.5 m along +X: the geometry reaches 0.854 m, outside; the check says by at least that.
    const ecs::Entity outside = addMesh(reg, octahedron(), turnedAt(cell + glm::vec3(0.5f, 0, 0)));
    const float exactOver = meshWorldBounds(reg, outside).overhang(Aabb::cube(cell, half));
    EXPECT_NEAR(exactOver, 0.5f + kR - half, 1e-6f);
    EXPECT_GT(exactOver, 0.f);
    EXPECT_GE(cellOverhang(reg, outside, cell, half), exactOver);
    // Leaving along Y (untouched by the turn): exact and conservative agree.
    const ecs::Entity up = addMesh(reg, octahedron(), turnedAt(cell + glm::vec3(0, 0.4f, 0)));
    EXPECT_NEAR(cellOverhang(reg, up, cell, half), 0.4f + 0.5f - half, 1e-6f);
}
