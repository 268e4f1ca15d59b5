#pragma once
// The path a walked reflector follows and the camera that chases it (the level walk).

#include "engine/math/camera.h"

#include <glm/vec3.hpp>

#include <utility>
#include <vector>

namespace specula {
class EmbreeScene;

namespace sandbox {

// Arc-length parameterised polyline.
struct Polyline {
    std::vector<glm::vec3> points;
    std::vector<float> cumulative; // length up to each point

    explicit Polyline(std::vector<glm::vec3> p);
    float length() const { return cumulative.back(); }
    // Point and unit tangent at fraction u in [0, 1] of the length.
    std::pair<glm::vec3, glm::vec3> at(float u) const;
};

// The chase camera: beside the path at `side` (+1 or -1), slightly above, looking at p.
CameraView chaseCamera(glm::vec3 p, glm::vec3 tangent, float side, int width, int height);

// Frames of the walk from which the camera on `side` sees the reflector centre unblocked.
int unblockedFrames(const EmbreeScene& env, const Polyline& path, float side, int frames);

} // namespace sandbox
} // namespace specula
