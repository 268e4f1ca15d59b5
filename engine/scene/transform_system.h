#pragma once
#include "engine/ecs/registry.h"
#include "engine/scene/components.h"

namespace specula {

// Recomputes Transform::world for every entity from its local TRS and parent chain.
void updateWorldTransforms(ecs::Registry& registry);

} // namespace specula
