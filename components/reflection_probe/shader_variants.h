#pragma once
// Compiled shader variants of one flavour, keyed by a typed variant (Filament's Variant
// idea): a small ordered struct whose filter() drops what the variant cannot use, so two
// requests that differ only in irrelevant bits share one program. A Variant provides
//   Variant filter() const;                          canonical form
//   std::string name() const;                        for stats and logs
//   gpu::Program build() const;                      sources + defines
// and operator<=>. Built on first use, kept for the system's lifetime. The probe's GLSL is
// compiled into this library and registered when a store's variants are created.
#include "engine/gpu/shader.h"
#include "engine/gpu/shader_files.h"

#include <map>
#include <string>
#include <vector>

namespace specula::gpu::embedded {
std::span<const ShaderFile> probeShaderFiles(); // generated: components/reflection_probe/**
} // namespace specula::gpu::embedded

namespace specula {

// A reflector pass: the shared vertex stage (shaders/reflector.vert) and a flavour's fragment
// stage `frag` with its permutation `defines` and OUTPUT (0 colour, 1.. the twin's inputs).
inline gpu::Program buildReflectorProgram(const char* frag, std::vector<std::string> defines,
                                          int output) {
    defines.push_back("OUTPUT=" + std::to_string(output));
    return gpu::buildProgram(
        gpu::ShaderSource::file("components/reflection_probe/shaders/reflector.vert"),
        gpu::ShaderSource::file(frag), defines);
}

template <typename Variant> class ShaderVariants {
public:
    ShaderVariants() { gpu::addShaderFiles(gpu::embedded::probeShaderFiles()); }

    gpu::Program& get(const Variant& requested) {
        const Variant v = requested.filter();
        auto it = programs_.find(v);
        if (it == programs_.end()) it = programs_.emplace(v, v.build()).first;
        return it->second;
    }

private:
    std::map<Variant, gpu::Program> programs_;
};

} // namespace specula
