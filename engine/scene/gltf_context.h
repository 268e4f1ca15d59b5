#pragma once
// Internal to the glTF loader (include gltf_loader.h instead): what every conversion step
// shares — the file name errors carry, the parsed model, and where warnings go.
#include "engine/core/error.h"
#include "engine/scene/tinygltf_config.h"

#include <climits>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace specula::gltf_internal {

// tinygltf addresses every file with 32-bit sizes, so no glTF, buffer or image file can be
// larger.
constexpr std::uint64_t kMaxGltfFileBytes = UINT_MAX;

// tinygltf and Draco report several problems separated by newlines; the project wants one
// line.
std::string oneLine(const std::string& text);

// "what[i]", the way glTF paths name an element of a top-level array.
std::string idx(const char* what, std::size_t i);

inline bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

class Context {
public:
    Context(std::string file, const tinygltf::Model& model, std::vector<std::string>& warnings)
        : file_(std::move(file)), model_(model), warnings_(warnings) {}

    const tinygltf::Model& model() const { return model_; }

    [[noreturn]] void fail(const std::string& field, const std::string& what) const {
        throw Error(file_, field, what);
    }
    void warn(const std::string& field, const std::string& what) {
        warnings_.push_back(field + ": " + what);
    }

    // Element `i` of one of the model's arrays, named `name`; `from` is the field that holds
    // the index.
    template <typename T>
    const T& at(const std::vector<T>& v, int i, const char* name, const std::string& from) const {
        if (i < 0 || std::size_t(i) >= v.size())
            fail(from, std::string(name) + " index " + std::to_string(i) + " out of range (" +
                           std::to_string(v.size()) + " " + name + ")");
        return v[std::size_t(i)];
    }

private:
    std::string file_;
    const tinygltf::Model& model_;
    std::vector<std::string>& warnings_;
};

} // namespace specula::gltf_internal
