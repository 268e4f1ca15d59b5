#include "engine/gpu/shader.h"

#include "engine/core/error.h"
#include "engine/gpu/shader_files.h"

#include <cstring>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

namespace specula::gpu {

namespace fs = std::filesystem;

fs::path shaderRoot() {
#ifdef SPECULA_SHADER_ROOT
    return fs::path(SPECULA_SHADER_ROOT);
#else
    return {}; // a library built without tests: every shader it uses is embedded
#endif
}

namespace {

// Mesa (22.x at least) ignores the source-string number of `#line` and reports every error
// as source 0, so the file index is also encoded in the line number itself: line L of file
// k is numbered k * kLineStride + L. Drivers that do honour the source number agree.
constexpr int kLineStride = 100000;

std::string lineDirective(std::size_t fileIndex, int line) {
    return "#line " + std::to_string(int(fileIndex) * kLineStride + line) + " " +
           std::to_string(fileIndex) + "\n";
}

fs::path resolve(const fs::path& p) {
    return p.is_absolute() ? p : shaderRoot() / p;
}

// A shader file's text: a relative path from the embedded tables first (shader_files.h), then
// from the disk under shaderRoot(); an absolute path from the disk. `key` identifies the file
// for the include-once rule, `where` says where it was looked for.
bool readShaderFile(const fs::path& p, std::string& out, fs::path& key, std::string& where) {
    if (!p.is_absolute()) {
        if (const auto text = embeddedShaderFile(p.generic_string())) {
            out.assign(*text);
            key = "embedded:" + p.lexically_normal().generic_string();
            return true;
        }
    }
    const fs::path onDisk = resolve(p);
    where = "not embedded; looked at " + onDisk.string();
    std::ifstream in(onDisk, std::ios::binary);
    if (!in) return false;
    std::ostringstream ss;
    ss << in.rdbuf();
    out = ss.str();
    key = fs::weakly_canonical(onDisk);
    return true;
}

std::string trimLeft(const std::string& s) {
    const auto i = s.find_first_not_of(" \t");
    return i == std::string::npos ? std::string() : s.substr(i);
}

bool startsWithDirective(const std::string& trimmed, const char* directive) {
    // "#  include" is legal preprocessor spelling, so skip blanks after '#'.
    if (trimmed.empty() || trimmed[0] != '#') return false;
    const std::string rest = trimLeft(trimmed.substr(1));
    const std::string d(directive);
    return rest.compare(0, d.size(), d) == 0 &&
           (rest.size() == d.size() || rest[d.size()] == ' ' || rest[d.size()] == '\t' ||
            rest[d.size()] == '"' || rest[d.size()] == '\r');
}

class Expander {
public:
    ExpandedSource out;

    void file(const std::string& name, const std::string& content, const fs::path& key, int depth) {
        if (!key.empty()) seen_.insert(key);
        const std::size_t index = out.files.size();
        out.files.push_back(name);
        out.text += lineDirective(index, 1);

        std::istringstream in(content);
        std::string line;
        int lineNo = 0;
        while (std::getline(in, line)) {
            ++lineNo;
            if (lineNo >= kLineStride)
                throw Error(name, "line " + std::to_string(lineNo),
                            "shader files are limited to " + std::to_string(kLineStride - 1) +
                                " lines (line numbers encode the file index)");
            const std::string t = trimLeft(line);
            if (startsWithDirective(t, "version")) {
                // The preamble already declared the version; an empty line keeps numbering.
                out.text += "\n";
                continue;
            }
            if (!startsWithDirective(t, "include")) {
                out.text += line + "\n";
                continue;
            }
            const auto q0 = t.find('"');
            const auto q1 = q0 == std::string::npos ? q0 : t.find('"', q0 + 1);
            if (q1 == std::string::npos)
                throw Error(name, "line " + std::to_string(lineNo),
                            "expected #include \"path\" (path relative to the repository root)");
            const std::string incName = t.substr(q0 + 1, q1 - q0 - 1);
            std::string incText, where;
            fs::path incKey;
            if (!readShaderFile(incName, incText, incKey, where))
                throw Error(name, "line " + std::to_string(lineNo),
                            "cannot open included file \"" + incName + "\" (" + where + ")");
            if (seen_.count(incKey)) {
                out.text += "\n";
                continue;
            }
            if (depth > 32)
                throw Error(name, "line " + std::to_string(lineNo),
                            "#include nesting deeper than 32 levels");
            file(incName, incText, incKey, depth + 1);
            out.text += lineDirective(index, lineNo + 1);
        }
    }

private:
    std::set<fs::path> seen_;
};

const char* stageName(GLenum stage) {
    switch (stage) {
    case GL_VERTEX_SHADER:
        return "vertex";
    case GL_FRAGMENT_SHADER:
        return "fragment";
    default:
        return "shader";
    }
}

std::string definesText(const std::vector<std::string>& defines) {
    std::string s;
    for (const auto& d : defines)
        s += (s.empty() ? "" : " ") + d;
    return s.empty() ? "none" : s;
}

Shader compile(GLenum stage, const ShaderSource& src, const std::vector<std::string>& defines) {
    const ExpandedSource ex = expandShader(src, defines);
    Shader sh = Shader::create(stage);
    const char* text = ex.text.c_str();
    glShaderSource(sh.id(), 1, &text, nullptr);
    glCompileShader(sh.id());
    GLint ok = GL_FALSE;
    glGetShaderiv(sh.id(), GL_COMPILE_STATUS, &ok);
    if (ok == GL_TRUE) return sh;

    GLint len = 0;
    glGetShaderiv(sh.id(), GL_INFO_LOG_LENGTH, &len);
    std::string log(std::size_t(len > 0 ? len : 1), '\0');
    glGetShaderInfoLog(sh.id(), GLsizei(log.size()), nullptr, log.data());
    log.resize(std::strlen(log.c_str()));
    std::string file;
    int line = 0;
    const std::string rewritten = rewriteShaderLog(log, ex.files, &file, &line);
    const std::string what = std::string("GLSL compile error in ") + stageName(stage) + " shader " +
                             src.name + " (defines: " + definesText(defines) + "):\n" + rewritten;
    if (file.empty()) throw Error(src.name, "compile", what);
    throw Error(file, "line " + std::to_string(line), what);
}

} // namespace

ShaderSource ShaderSource::file(fs::path path) {
    ShaderSource s;
    s.name = path.string();
    s.path = std::move(path);
    return s;
}

ShaderSource ShaderSource::text(std::string name, std::string source) {
    ShaderSource s;
    s.name = std::move(name);
    s.source = std::move(source);
    return s;
}

ExpandedSource expandShader(const ShaderSource& src, const std::vector<std::string>& defines) {
    Expander ex;
    ex.out.files.push_back("<preamble>");
    ex.out.text = "#version 450 core\n";
    for (const auto& d : defines) {
        const auto eq = d.find('=');
        if (d.empty() || eq == 0)
            throw Error(src.name, "defines", "expected NAME or NAME=value, got \"" + d + "\"");
        ex.out.text += "#define " +
                       (eq == std::string::npos ? d : d.substr(0, eq) + " " + d.substr(eq + 1)) +
                       "\n";
    }
    if (src.path.empty()) {
        ex.file(src.name, src.source, {}, 0);
    } else {
        std::string content, where;
        fs::path key;
        if (!readShaderFile(src.path, content, key, where))
            throw Error(src.name, "shader file", "cannot open (" + where + ")");
        ex.file(src.name, content, key, 0);
    }
    return std::move(ex.out);
}

std::string rewriteShaderLog(const std::string& log, const std::vector<std::string>& files,
                             std::string* firstFile, int* firstLine) {
    // Mesa: "0:12(5): error: ...", NVIDIA: "0(12) : error C0000: ...",
    // AMD / Intel on Windows, glslang: "ERROR: 0:12: ...".
    static const std::regex mesa(R"(^(\d+):(\d+)\((\d+)\):\s*(.*)$)");
    static const std::regex nvidia(R"(^(\d+)\((\d+)\)\s*:\s*(.*)$)");
    static const std::regex glslang(R"(^(ERROR|WARNING):\s*(\d+):(\d+):\s*(.*)$)");
    // Returns the file name and rewrites `line` to the line within that file.
    auto locate = [&](const std::string& sourceNum, int& line) {
        std::size_t i = std::stoul(sourceNum);
        if (line >= kLineStride) {
            i = std::size_t(line / kLineStride);
            line %= kLineStride;
        }
        return i < files.size() ? files[i] : "<source string " + std::to_string(i) + ">";
    };
    std::istringstream in(log);
    std::string line, out;
    bool found = false;
    while (std::getline(in, line)) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::smatch m;
        std::string file, rest;
        int lineNo = 0;
        if (std::regex_match(line, m, mesa)) {
            lineNo = std::stoi(m[2]);
            file = locate(m[1], lineNo);
            rest = ":" + m[3].str() + ": " + m[4].str();
        } else if (std::regex_match(line, m, nvidia)) {
            lineNo = std::stoi(m[2]);
            file = locate(m[1], lineNo);
            rest = ": " + m[3].str();
        } else if (std::regex_match(line, m, glslang)) {
            lineNo = std::stoi(m[3]);
            file = locate(m[2], lineNo);
            rest = ": " + std::string(m[1].str() == "ERROR" ? "error: " : "warning: ") + m[4].str();
        } else {
            out += line + "\n";
            continue;
        }
        out += file + ":" + std::to_string(lineNo) + rest + "\n";
        const bool isError =
            rest.find("error") != std::string::npos || rest.find("ERROR") != std::string::npos;
        if (!found && isError) {
            found = true;
            if (firstFile) *firstFile = file;
            if (firstLine) *firstLine = lineNo;
        }
    }
    return out;
}

Program buildProgram(const ShaderSource& vert, const ShaderSource& frag,
                     const std::vector<std::string>& defines) {
    Shader vs = compile(GL_VERTEX_SHADER, vert, defines);
    Shader fs = compile(GL_FRAGMENT_SHADER, frag, defines);
    Program p = Program::create();
    glAttachShader(p.id(), vs.id());
    glAttachShader(p.id(), fs.id());
    glLinkProgram(p.id());
    GLint ok = GL_FALSE;
    glGetProgramiv(p.id(), GL_LINK_STATUS, &ok);
    glDetachShader(p.id(), vs.id());
    glDetachShader(p.id(), fs.id());
    if (ok == GL_TRUE) return p;

    GLint len = 0;
    glGetProgramiv(p.id(), GL_INFO_LOG_LENGTH, &len);
    std::string log(std::size_t(len > 0 ? len : 1), '\0');
    glGetProgramInfoLog(p.id(), GLsizei(log.size()), nullptr, log.data());
    log.resize(std::strlen(log.c_str()));
    throw Error(vert.name + " + " + frag.name, "link",
                "GLSL link error (defines: " + definesText(defines) + "):\n" + log);
}

} // namespace specula::gpu
