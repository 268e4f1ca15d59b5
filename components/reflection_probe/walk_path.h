#pragma once
// The paths the reflectors walk (specula-sandbox walk, and a PEM whose parameter is the
// reflector's position): where the reflectors are at time t in [0, 1), as an offset from
// where the scene authors them. Every path is a closed loop (t = 1 is t = 0 again) and stays
// within the walk amplitude of the authored position on each axis.

#include <string>

#include <glm/vec3.hpp>

namespace specula {

enum class WalkPath { Orbit, Line, Figure8 };
// The name of the one open path: the scene camera's glTF animation (cameraPathView), which
// only the viewpoint follows, so it is no WalkPath.
inline constexpr const char* kCameraPathName = "camera";
bool parseWalkPath(const std::string& s, WalkPath& out);
const char* toString(WalkPath p);
glm::vec3 walkOffset(WalkPath path, float t, float amplitude);

} // namespace specula
