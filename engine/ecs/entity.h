#pragma once
// An entity is an index into the registry's slots plus the generation of that slot when
// the handle was made. Destroying an entity bumps the slot's generation, so every old
// handle to it becomes detectably stale even after the slot is reused.
#include <cstdint>
#include <functional>

namespace specula::ecs {

struct Entity {
    std::uint32_t index = UINT32_MAX;
    std::uint32_t generation = 0;

    constexpr bool isNull() const { return index == UINT32_MAX; }
    friend constexpr bool operator==(Entity, Entity) = default;
};

inline constexpr Entity kNullEntity{};

} // namespace specula::ecs

template <> struct std::hash<specula::ecs::Entity> {
    std::size_t operator()(specula::ecs::Entity e) const noexcept {
        return std::hash<std::uint64_t>{}((std::uint64_t(e.generation) << 32) | e.index);
    }
};
