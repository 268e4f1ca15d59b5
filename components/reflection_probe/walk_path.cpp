#include "walk_path.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>

namespace specula {

bool parseWalkPath(const std::string& s, WalkPath& out) {
    if (s == "orbit")
        out = WalkPath::Orbit;
    else if (s == "line")
        out = WalkPath::Line;
    else if (s == "figure8")
        out = WalkPath::Figure8;
    else
        return false;
    return true;
}

const char* toString(WalkPath p) {
    switch (p) {
    case WalkPath::Orbit:
        return "orbit";
    case WalkPath::Line:
        return "line";
    case WalkPath::Figure8:
        return "figure8";
    }
    return "?";
}

glm::vec3 walkOffset(WalkPath path, float t, float amplitude) {
    const float a = amplitude;
    const float w = glm::two_pi<float>() * t;
    switch (path) {
    case WalkPath::Orbit:
        return {a * std::sin(w), 0.25f * a * std::sin(2.f * w), a * std::cos(w)};
    case WalkPath::Line:
        return {a * std::sin(w), 0.f, 0.f};
    case WalkPath::Figure8:
        return {a * std::sin(w), 0.f, a * std::sin(2.f * w)};
    }
    return glm::vec3(0.f);
}

} // namespace specula
