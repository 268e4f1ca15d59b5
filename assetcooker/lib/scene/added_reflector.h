#pragma once
// A test mirror dropped into an opened scene (specula-sandbox walk/bench --add-reflector):
// a sphere or an axis-aligned box, a perfect mirror (metallic 1, roughness 0, f0 < 0), added
// as one more root node entity with Name, Transform and Mesh, so the renderer, Embree, the
// cooker and the walk (ReflectorRoots) treat it like a reflector node of the glTF.
#include "engine/ecs/entity.h"

#include <string>

#include <glm/vec3.hpp>

namespace specula {

struct ProbeScene;

struct AddedReflector {
    enum class Shape { Sphere, Box };
    Shape shape = Shape::Sphere;
    glm::vec3 centre{0.f}; // world space, metres
    float radius = 0.f;    // sphere
    glm::vec3 size{0.f};   // box: full edge lengths along x, y, z
};

// The flag the specs come from, for messages.
inline constexpr const char* kAddReflectorFlag = "--add-reflector";
// What the flag takes, for help texts: "sphere:x,y,z,r or box:x,y,z,sx,sy,sz".
inline constexpr const char* kAddReflectorForms = "sphere:x,y,z,r or box:x,y,z,sx,sy,sz";

// Parses "sphere:x,y,z,r" or "box:x,y,z,sx,sy,sz" (finite numbers, |x| <= 1e6; r and the
// sizes > 0). Throws UsageError naming --add-reflector and what is wrong: an unknown shape,
// the wrong count of numbers, a non-number, a non-finite one, a radius or size <= 0.
AddedReflector parseAddedReflector(const std::string& spec);
// The spec back in the flag's form ("sphere:0,1.2,0,0.3"), for logs.
std::string describeAddedReflector(const AddedReflector& r);

// Adds `r` to the opened scene: a root entity named added_reflector_N (the first N no node
// of the scene is named), its mesh (sphere: 48 x 24 UV sphere, box: 24 vertices with face
// normals, both with outward normals and counter-clockwise fronts), a ReflectorMarkup
// (f0 -1: a perfect mirror) and its mirrorEntities entry; extends the scene's bounds and
// updates the world transforms. The default camera (sceneCameraView) is searched again on
// its next use. Returns the new entity.
ecs::Entity addReflector(ProbeScene& scene, const AddedReflector& r);

} // namespace specula
