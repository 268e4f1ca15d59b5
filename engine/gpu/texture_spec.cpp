#include "engine/gpu/texture_spec.h"

#include "engine/core/error.h"

#include <algorithm>
#include <cstdio>

namespace specula::gpu {

Texture createTexture(const TextureSpec& spec) {
    Texture texture = Texture::create(spec.target);
    if (spec.target == GL_TEXTURE_2D)
        glTextureStorage2D(texture.id(), spec.levels, spec.internalFormat, spec.width, spec.height);
    else
        glTextureStorage3D(texture.id(), spec.levels, spec.internalFormat, spec.width, spec.height,
                           spec.layers);
    return texture;
}

std::string internalFormatName(GLenum format) {
    switch (format) {
    case GL_RGBA32F:
        return "GL_RGBA32F";
    case GL_RGBA16F:
        return "GL_RGBA16F";
    case GL_R32F:
        return "GL_R32F";
    case GL_R16F:
        return "GL_R16F";
    case GL_RGBA16I:
        return "GL_RGBA16I";
    case GL_COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT:
        return "GL_COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT";
    default:
        break;
    }
    char hex[16];
    std::snprintf(hex, sizeof hex, "0x%04x", unsigned(format));
    return hex;
}

namespace {

std::string targetName(GLint target) {
    switch (target) {
    case GL_TEXTURE_2D:
        return "GL_TEXTURE_2D";
    case GL_TEXTURE_2D_ARRAY:
        return "GL_TEXTURE_2D_ARRAY";
    case GL_TEXTURE_CUBE_MAP:
        return "GL_TEXTURE_CUBE_MAP";
    case GL_TEXTURE_3D:
        return "GL_TEXTURE_3D";
    default:
        return internalFormatName(GLenum(target));
    }
}

std::string differs(const char* what, const std::string& got, const std::string& expected) {
    return std::string(what) + " is " + got + ", " + expected + " expected";
}

} // namespace

std::string textureMismatch(GLuint id, const TextureSpec& spec) {
    if (id == 0 || !glIsTexture(id)) return "texture " + std::to_string(id) + " is not a texture";
    GLint target = 0, immutable = 0, levels = 0;
    glGetTextureParameteriv(id, GL_TEXTURE_TARGET, &target);
    if (GLenum(target) != spec.target)
        return differs("target", targetName(target), targetName(GLint(spec.target)));
    glGetTextureParameteriv(id, GL_TEXTURE_IMMUTABLE_FORMAT, &immutable);
    if (!immutable) return "storage is not immutable: allocate it with glTextureStorage*";
    GLint format = 0, width = 0, height = 0, depth = 0;
    glGetTextureLevelParameteriv(id, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
    if (GLenum(format) != spec.internalFormat)
        return differs("internal format", internalFormatName(GLenum(format)),
                       internalFormatName(spec.internalFormat));
    glGetTextureLevelParameteriv(id, 0, GL_TEXTURE_WIDTH, &width);
    glGetTextureLevelParameteriv(id, 0, GL_TEXTURE_HEIGHT, &height);
    glGetTextureLevelParameteriv(id, 0, GL_TEXTURE_DEPTH, &depth);
    const int layers = spec.target == GL_TEXTURE_2D ? 1 : spec.layers;
    auto size = [](int w, int h, int d) {
        return std::to_string(w) + "x" + std::to_string(h) + "x" + std::to_string(d);
    };
    if (width != spec.width || height != spec.height || depth != layers)
        return differs("size", size(width, height, depth), size(spec.width, spec.height, layers));
    glGetTextureParameteriv(id, GL_TEXTURE_IMMUTABLE_LEVELS, &levels);
    if (levels != spec.levels)
        return differs("mip levels", std::to_string(levels), std::to_string(spec.levels));
    return {};
}

std::string uniformBufferMismatch(GLuint id, std::size_t bytes) {
    if (id == 0 || !glIsBuffer(id)) return "buffer " + std::to_string(id) + " is not a buffer";
    GLint64 size = 0;
    GLint immutable = 0, flags = 0;
    glGetNamedBufferParameteri64v(id, GL_BUFFER_SIZE, &size);
    if (size < GLint64(bytes))
        return "holds " + std::to_string(size) + " bytes, " + std::to_string(bytes) + " expected";
    glGetNamedBufferParameteriv(id, GL_BUFFER_IMMUTABLE_STORAGE, &immutable);
    glGetNamedBufferParameteriv(id, GL_BUFFER_STORAGE_FLAGS, &flags);
    if (immutable && !(GLbitfield(flags) & GL_DYNAMIC_STORAGE_BIT))
        return "immutable storage without GL_DYNAMIC_STORAGE_BIT: the runtime rewrites it";
    return {};
}

TextureAllocator hostTextureAllocator(std::vector<HostTexture> textures, std::string file) {
    return [textures = std::move(textures), file = std::move(file)](const TextureSpec& spec) {
        const auto found = std::find_if(textures.begin(), textures.end(),
                                        [&](const HostTexture& t) { return t.name == spec.name; });
        const std::string field = "textures." + spec.name;
        if (found == textures.end())
            throw Error(file, field,
                        "the host handed no texture of this name (unmanaged mode needs every "
                        "texture the probe's description lists)");
        if (const std::string mismatch = textureMismatch(found->id, spec); !mismatch.empty())
            throw Error(file, field, mismatch);
        return Texture::borrow(found->id, spec.target);
    };
}

} // namespace specula::gpu
