#pragma once
// `specula-cook inspect`: what a glTF file holds, as one JSON object.
#include <nlohmann/json.hpp>

#include <string>

namespace specula::cook {

// Loads `path` into a scratch registry and summarises it: meshes, primitives, vertices,
// triangles (counted once per mesh, see LoadedScene), world bounds, extensionsUsed, nodes,
// materials, warnings. Throws specula::Error when the file cannot be loaded.
nlohmann::json inspectScene(const std::string& path);

} // namespace specula::cook
