#include "engine/gpu/gl_objects.h"

#include <glm/gtc/type_ptr.hpp>

namespace specula::gpu {

Buffer Buffer::create() {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    Buffer b;
    static_cast<GlName&>(b) = GlName::adopt(id);
    return b;
}

Buffer Buffer::create(const void* data, GLsizeiptr bytes, GLbitfield flags) {
    Buffer b = create();
    // Zero-sized storage is an error in GL; a one-byte buffer keeps empty meshes legal.
    glNamedBufferStorage(b.id(), bytes > 0 ? bytes : 1, bytes > 0 ? data : nullptr, flags);
    return b;
}

Texture Texture::create(GLenum target) {
    GLuint id = 0;
    glCreateTextures(target, 1, &id);
    Texture t;
    static_cast<GlName&>(t) = GlName::adopt(id);
    t.target_ = target;
    return t;
}

Texture Texture::borrow(GLuint id, GLenum target) {
    Texture t;
    static_cast<GlName&>(t) = GlName::borrow(id);
    t.target_ = target;
    return t;
}

Framebuffer Framebuffer::create() {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    Framebuffer f;
    static_cast<GlName&>(f) = GlName::adopt(id);
    return f;
}

Renderbuffer Renderbuffer::create() {
    GLuint id = 0;
    glCreateRenderbuffers(1, &id);
    Renderbuffer r;
    static_cast<GlName&>(r) = GlName::adopt(id);
    return r;
}

VertexArray VertexArray::create() {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    VertexArray v;
    static_cast<GlName&>(v) = GlName::adopt(id);
    return v;
}

Query Query::create(GLenum target) {
    GLuint id = 0;
    glCreateQueries(target, 1, &id);
    Query q;
    static_cast<GlName&>(q) = GlName::adopt(id);
    q.target_ = target;
    return q;
}

Shader Shader::create(GLenum stage) {
    Shader s;
    static_cast<GlName&>(s) = GlName::adopt(glCreateShader(stage));
    return s;
}

Program Program::create() {
    Program p;
    p.id_ = glCreateProgram();
    return p;
}

void Program::reset() {
    if (id_) glDeleteProgram(id_);
    id_ = 0;
    locations_.clear();
}

GLint Program::uniformLocation(const std::string& name) const {
    auto it = locations_.find(name);
    if (it != locations_.end()) return it->second;
    const GLint loc = glGetUniformLocation(id_, name.c_str());
    locations_.emplace(name, loc);
    return loc;
}

void Program::setUniform(const std::string& name, int v) {
    glProgramUniform1i(id_, uniformLocation(name), v);
}
void Program::setUniform(const std::string& name, unsigned v) {
    glProgramUniform1ui(id_, uniformLocation(name), v);
}
void Program::setUniform(const std::string& name, float v) {
    glProgramUniform1f(id_, uniformLocation(name), v);
}
void Program::setUniform(const std::string& name, const glm::vec2& v) {
    glProgramUniform2fv(id_, uniformLocation(name), 1, glm::value_ptr(v));
}
void Program::setUniform(const std::string& name, const glm::vec3& v) {
    glProgramUniform3fv(id_, uniformLocation(name), 1, glm::value_ptr(v));
}
void Program::setUniform(const std::string& name, const glm::vec4& v) {
    glProgramUniform4fv(id_, uniformLocation(name), 1, glm::value_ptr(v));
}
void Program::setUniform(const std::string& name, const glm::ivec2& v) {
    glProgramUniform2iv(id_, uniformLocation(name), 1, glm::value_ptr(v));
}
void Program::setUniform(const std::string& name, const glm::mat3& v) {
    glProgramUniformMatrix3fv(id_, uniformLocation(name), 1, GL_FALSE, glm::value_ptr(v));
}
void Program::setUniform(const std::string& name, const glm::mat4& v) {
    glProgramUniformMatrix4fv(id_, uniformLocation(name), 1, GL_FALSE, glm::value_ptr(v));
}

} // namespace specula::gpu
