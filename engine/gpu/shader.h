#pragma once
// GLSL programs built from files, with permutation defines and `#include "path"`.
//
// What the compiler sees: `#version 450 core`, one `#define` per permutation define, then
// the stage file with every `#include` replaced by the included file (each file at most
// once per stage, recursively). Every file gets its own GLSL source-string number in
// `#line` directives, and line L of file k is numbered k * 100000 + L (Mesa ignores source
// numbers), so a compile error is rethrown as a specula::Error naming the real file and
// line, whatever the driver (Mesa `0:12(5): error:`, NVIDIA `0(12) : error`).
#include "engine/gpu/gl_objects.h"

#include <filesystem>
#include <string>
#include <vector>

namespace specula::gpu {

// Where relative shader paths that no library embeds are looked for: the repository root in a
// build with tests (their own shaders; the SPECULA_SHADER_ROOT compile definition), else empty.
// Every shader the runtime and the tools use is embedded (shader_files.h).
std::filesystem::path shaderRoot();

struct ShaderSource {
    // A file: relative to shaderRoot(), or absolute.
    static ShaderSource file(std::filesystem::path path);
    // Source text given directly; `name` stands for the file in error messages. Its
    // #includes are still resolved against shaderRoot().
    static ShaderSource text(std::string name, std::string source);

    std::filesystem::path path; // empty for text sources
    std::string name;
    std::string source;
};

// Expands defines and includes for one stage: the exact text handed to the compiler, and
// the file name behind each file index (index 0 is the preamble: #version and defines).
struct ExpandedSource {
    std::string text;
    std::vector<std::string> files;
};
// Each define is "NAME" (-> `#define NAME`) or "NAME=value" (-> `#define NAME value`).
ExpandedSource expandShader(const ShaderSource& src, const std::vector<std::string>& defines);

// Compiles and links a vertex + fragment program. Throws specula::Error on a missing file,
// a compile error (file and line of the first error; the whole log, rewritten to real
// file names, in the message) or a link error.
Program buildProgram(const ShaderSource& vert, const ShaderSource& frag,
                     const std::vector<std::string>& defines = {});

// Rewrites a driver info log so source-string numbers read as file names ("file:line: ...").
// Returns the file and line of the first error found, if any, through `firstFile`/`firstLine`.
std::string rewriteShaderLog(const std::string& log, const std::vector<std::string>& files,
                             std::string* firstFile = nullptr, int* firstLine = nullptr);

} // namespace specula::gpu
