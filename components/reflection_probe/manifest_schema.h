#pragma once
// The manifests' JSON Schemas (docs/formats/*.schema.json), compiled into the runtime like its
// GLSL: the one place every member of every manifest is declared. The tests validate what the
// cooker writes against them; a reader uses them to name the members of a newer minor format
// that it ignores (asset_format.h).
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace specula {

// The text of docs/formats/<name>.schema.json ("probe-distance", "level", ...), or nullopt.
std::optional<std::string_view> manifestSchemaText(std::string_view name);

// The members of `manifest` that schema `name` does not declare, as paths with array indices
// written "[]" ("layers[].tint"), each once, in document order. Follows the schema's
// "properties", "items" and local "$ref"s; a member declared without "properties" (free-form,
// such as the effect plan) is not looked into. Throws Error when there is no such schema.
std::vector<std::string> undeclaredMembers(const nlohmann::json& manifest, std::string_view name);

} // namespace specula
