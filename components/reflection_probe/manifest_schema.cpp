#include "manifest_schema.h"

#include "engine/core/error.h"
#include "engine/gpu/shader_files.h"

#include <map>
#include <set>

namespace specula {

namespace gpu::embedded {
std::span<const ShaderFile> manifestSchemaFiles(); // generated: docs/formats/*.schema.json
} // namespace gpu::embedded

using nlohmann::json;

namespace {

constexpr std::string_view kFolder = "docs/formats/";
constexpr std::string_view kSuffix = ".schema.json";

// Resolves local references ("#/$defs/NAME"); our schemas use no other kind.
const json& resolve(const json& root, const json& node) {
    const json* n = &node;
    for (int hops = 0; n->is_object() && n->contains("$ref") && hops < 16; ++hops) {
        const std::string ref = (*n)["$ref"].get<std::string>();
        constexpr std::string_view kDefs = "#/$defs/";
        if (ref.rfind(kDefs, 0) != 0) break;
        n = &root.at("$defs").at(ref.substr(kDefs.size()));
    }
    return *n;
}

struct Walk {
    const json& root;
    std::vector<std::string> found;
    std::set<std::string> seen;

    void visit(const json& schemaNode, const json& value, const std::string& path) {
        const json& s = resolve(root, schemaNode);
        if (!s.is_object()) return;
        if (value.is_object() && s.contains("properties")) {
            const json& declared = s["properties"];
            for (const auto& [key, member] : value.items()) {
                const std::string at = path.empty() ? key : path + "." + key;
                if (declared.contains(key))
                    visit(declared[key], member, at);
                else if (seen.insert(at).second)
                    found.push_back(at);
            }
        } else if (value.is_array() && s.contains("items")) {
            for (const json& element : value)
                visit(s["items"], element, path + "[]");
        }
    }
};

const json& parsedSchema(std::string_view name) {
    // Parsed once per schema; the table is tiny and fixed at build time.
    static const std::map<std::string, json, std::less<>> schemas = [] {
        std::map<std::string, json, std::less<>> all;
        for (const gpu::ShaderFile& f : gpu::embedded::manifestSchemaFiles()) {
            std::string_view n = f.path.substr(kFolder.size());
            n.remove_suffix(kSuffix.size());
            all.emplace(std::string(n), json::parse(f.text));
        }
        return all;
    }();
    const auto it = schemas.find(name);
    if (it == schemas.end())
        throw Error(std::string(kFolder) + std::string(name) + std::string(kSuffix), "",
                    "no such manifest schema in this runtime");
    return it->second;
}

} // namespace

std::optional<std::string_view> manifestSchemaText(std::string_view name) {
    for (const gpu::ShaderFile& f : gpu::embedded::manifestSchemaFiles())
        if (f.path.substr(kFolder.size()) == std::string(name) + std::string(kSuffix))
            return f.text;
    return std::nullopt;
}

std::vector<std::string> undeclaredMembers(const json& manifest, std::string_view name) {
    const json& schema = parsedSchema(name);
    Walk walk{schema, {}, {}};
    walk.visit(schema, manifest, "");
    return walk.found;
}

} // namespace specula
