#include "transform_system.h"

#include <glm/gtc/matrix_transform.hpp>

#include <unordered_map>

namespace specula {

glm::mat4 Transform::local() const {
    return glm::translate(glm::mat4(1.f), translation) * glm::mat4_cast(rotation) *
           glm::scale(glm::mat4(1.f), scale);
}

namespace {
glm::mat4 worldOf(ecs::Registry& reg, ecs::Entity e,
                  std::unordered_map<std::uint32_t, glm::mat4>& memo, int depth) {
    if (auto it = memo.find(e.index); it != memo.end()) return it->second;
    Transform* t = reg.find<Transform>(e);
    if (!t) return glm::mat4(1.f);
    glm::mat4 m = t->local();
    // Depth guard: a malformed hierarchy with a cycle must not recurse forever.
    if (!t->parent.isNull() && reg.valid(t->parent) && depth < 1024)
        m = worldOf(reg, t->parent, memo, depth + 1) * m;
    memo[e.index] = m;
    return m;
}
} // namespace

void updateWorldTransforms(ecs::Registry& registry) {
    std::unordered_map<std::uint32_t, glm::mat4> memo;
    registry.view<Transform>().each(
        [&](ecs::Entity e, Transform& t) { t.world = worldOf(registry, e, memo, 0); });
}

} // namespace specula
