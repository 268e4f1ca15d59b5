#pragma once
// How far a scene's reflectors may walk (walk_path.h) and stay inside their probe's cell: the
// tools' side of the walk paths, which needs the opened scene.
#include "assetcooker/lib/scene/probe_setup.h"

#include <glm/vec3.hpp>

namespace specula {

// How far the reflectors may move from where they were authored on every axis and stay
// inside the probe's cell (markupProbeCentre, markupCellSize): at most a fifth of the cell,
// never more than the room they have. `currentOffset`: how far they stand from their authored
// position now (taken away from their current bounds).
float walkAmplitude(const ProbeScene& scene, glm::vec3 currentOffset);

} // namespace specula
