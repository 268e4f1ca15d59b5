#pragma once
// GLSL files compiled into the libraries (cmake/SpeculaShaders.cmake), found by their
// repository-relative paths: programs never depend on the source tree being where the build
// left it (an installed library, a copied binary, a parent project's build).
//
// Each library that owns shaders registers its table once before building programs; the
// engine's own GLSL (engine/**) is always registered. buildProgram reads a registered file
// first and falls back to the disk under shaderRoot() only for paths no library embeds (a
// test's own shaders).
#include <optional>
#include <span>
#include <string_view>

namespace specula::gpu {

struct ShaderFile {
    std::string_view path; // relative to the repository root, '/'-separated
    std::string_view text;
};

// Makes `files` findable by path. Idempotent; the views must outlive the process (they point
// at static tables).
void addShaderFiles(std::span<const ShaderFile> files);

// The registered text of a repository-relative path (normalised: "a/./b" is "a/b").
std::optional<std::string_view> embeddedShaderFile(std::string_view path);

namespace embedded {
std::span<const ShaderFile> engineShaderFiles(); // generated: engine/**
} // namespace embedded

} // namespace specula::gpu
