#pragma once
// A level bake's flavour settings as the shard list stores them (shard_bake.h), and the
// list's required-member reader: both errors name the file and the field.
#include "assetcooker/lib/bake/cook.h"
#include "engine/core/error.h"

#include <nlohmann/json.hpp>

#include <string>

namespace specula {

// The flavour's settings as JSON and back (for the shard list and the shard hash).
nlohmann::json cookSettingsToJson(const CookFlavour& flavour);
CookFlavour cookSettingsFromJson(const nlohmann::json& j, const std::string& file);

// j[name] as a T; Error(file, field + name) when it is missing or of the wrong type.
template <class T>
T jsonMember(const nlohmann::json& j, const char* name, const std::string& file,
             const std::string& field) {
    if (!j.is_object() || !j.contains(name))
        throw Error(file, field + name, "missing from the shard list");
    try {
        return j.at(name).get<T>();
    } catch (const nlohmann::json::exception&) {
        throw Error(file, field + name, "has the wrong type");
    }
}

} // namespace specula
