#pragma once
// Move-only owners of OpenGL object names, created with the GL 4.5 glCreate* calls so they
// are usable with direct state access (glNamedBuffer*, glTexture*, ...) without binding.
// A default-constructed wrapper owns nothing (id() == 0); a borrowed one (borrow) uses a
// name someone else owns and never deletes it. Destroy them while the context that made them
// is current.
#include <epoxy/gl.h>

#include <glm/glm.hpp>

#include <string>
#include <type_traits>
#include <unordered_map>
#include <utility>

namespace specula::gpu {

namespace detail {
// One owner template; Traits supplies the delete call.
template <typename Traits> class GlName {
public:
    GlName() = default;
    ~GlName() { reset(); }
    GlName(GlName&& o) noexcept
        : id_(std::exchange(o.id_, 0)), owned_(std::exchange(o.owned_, true)) {}
    GlName& operator=(GlName&& o) noexcept {
        if (this != &o) {
            reset();
            id_ = std::exchange(o.id_, 0);
            owned_ = std::exchange(o.owned_, true);
        }
        return *this;
    }
    GlName(const GlName&) = delete;
    GlName& operator=(const GlName&) = delete;

    GLuint id() const { return id_; }
    explicit operator bool() const { return id_ != 0; }
    void reset() {
        if (id_ && owned_) Traits::destroy(id_);
        id_ = 0;
        owned_ = true;
    }
    bool owned() const { return owned_; }
    // Takes ownership of a name made elsewhere.
    static GlName adopt(GLuint id) {
        GlName n;
        n.id_ = id;
        return n;
    }
    // Uses a name its maker keeps owning (a host engine's texture handed to the runtime).
    static GlName borrow(GLuint id) {
        GlName n;
        n.id_ = id;
        n.owned_ = false;
        return n;
    }

private:
    GLuint id_ = 0;
    bool owned_ = true;
};

struct BufferTraits {
    static void destroy(GLuint id) { glDeleteBuffers(1, &id); }
};
struct TextureTraits {
    static void destroy(GLuint id) { glDeleteTextures(1, &id); }
};
struct FramebufferTraits {
    static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); }
};
struct RenderbufferTraits {
    static void destroy(GLuint id) { glDeleteRenderbuffers(1, &id); }
};
struct VertexArrayTraits {
    static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); }
};
struct QueryTraits {
    static void destroy(GLuint id) { glDeleteQueries(1, &id); }
};
struct ShaderTraits {
    static void destroy(GLuint id) { glDeleteShader(id); }
};
} // namespace detail

class Buffer : public detail::GlName<detail::BufferTraits> {
public:
    Buffer() = default;
    static Buffer create();
    // Immutable storage (glNamedBufferStorage) holding `bytes` copied from `data`.
    static Buffer create(const void* data, GLsizeiptr bytes, GLbitfield flags = 0);
};

// One std140 struct in a uniform buffer: created on the first upload, rewritten in place
// (no new storage) on later ones, bound to a binding point while drawing. T is a struct
// shared with GLSL whose layout the caller has checked with static_asserts.
template <typename T> class UniformBuffer {
    static_assert(std::is_trivially_copyable_v<T>, "uploaded byte for byte");

public:
    // Uploads go to `buffer` (at least sizeof(T) bytes, writable by glNamedBufferSubData), which
    // its maker keeps owning.
    static UniformBuffer borrow(GLuint buffer) {
        UniformBuffer u;
        static_cast<detail::GlName<detail::BufferTraits>&>(u.buffer_) =
            detail::GlName<detail::BufferTraits>::borrow(buffer);
        return u;
    }
    void upload(const T& value) {
        if (!buffer_)
            buffer_ = Buffer::create(&value, sizeof(T), GL_DYNAMIC_STORAGE_BIT);
        else
            glNamedBufferSubData(buffer_.id(), 0, sizeof(T), &value);
    }
    void bind(GLuint binding) const { glBindBufferBase(GL_UNIFORM_BUFFER, binding, buffer_.id()); }
    GLuint id() const { return buffer_.id(); }
    explicit operator bool() const { return bool(buffer_); }

private:
    Buffer buffer_;
};

class Texture : public detail::GlName<detail::TextureTraits> {
public:
    Texture() = default;
    static Texture create(GLenum target);
    // `id`, a texture of `target` its maker keeps owning.
    static Texture borrow(GLuint id, GLenum target);
    GLenum target() const { return target_; }

private:
    GLenum target_ = 0;
};

class Framebuffer : public detail::GlName<detail::FramebufferTraits> {
public:
    static Framebuffer create();
};

class Renderbuffer : public detail::GlName<detail::RenderbufferTraits> {
public:
    static Renderbuffer create();
};

class VertexArray : public detail::GlName<detail::VertexArrayTraits> {
public:
    static VertexArray create();
};

class Query : public detail::GlName<detail::QueryTraits> {
public:
    Query() = default;
    static Query create(GLenum target);
    GLenum target() const { return target_; }

private:
    GLenum target_ = 0;
};

class Shader : public detail::GlName<detail::ShaderTraits> {
public:
    static Shader create(GLenum stage);
};

// A linked program. Uniform setters use glProgramUniform* (no glUseProgram needed) and
// cache locations by name; a name the linker optimised away is silently ignored, as GL
// does for location -1.
class Program {
public:
    Program() = default;
    static Program create();
    ~Program() { reset(); }
    Program(Program&& o) noexcept
        : id_(std::exchange(o.id_, 0)), locations_(std::move(o.locations_)) {}
    Program& operator=(Program&& o) noexcept {
        if (this != &o) {
            reset();
            id_ = std::exchange(o.id_, 0);
            locations_ = std::move(o.locations_);
        }
        return *this;
    }
    Program(const Program&) = delete;
    Program& operator=(const Program&) = delete;

    GLuint id() const { return id_; }
    explicit operator bool() const { return id_ != 0; }
    void reset();
    void use() const { glUseProgram(id_); }

    GLint uniformLocation(const std::string& name) const;
    bool hasUniform(const std::string& name) const { return uniformLocation(name) >= 0; }

    void setUniform(const std::string& name, int v);
    void setUniform(const std::string& name, unsigned v);
    void setUniform(const std::string& name, float v);
    void setUniform(const std::string& name, const glm::vec2& v);
    void setUniform(const std::string& name, const glm::vec3& v);
    void setUniform(const std::string& name, const glm::vec4& v);
    void setUniform(const std::string& name, const glm::ivec2& v);
    void setUniform(const std::string& name, const glm::mat3& v);
    void setUniform(const std::string& name, const glm::mat4& v);

private:
    GLuint id_ = 0;
    mutable std::unordered_map<std::string, GLint> locations_;
};

} // namespace specula::gpu
