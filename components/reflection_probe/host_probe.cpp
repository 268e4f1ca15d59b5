#include "host_probe.h"

#include "engine/core/error.h"
#include "engine/gpu/shader.h"

namespace specula {

std::string missingHostGlFeature(int faceRes, int layers) {
    if (glGetString(GL_VERSION) == nullptr) return "no current OpenGL context";
    const int version = epoxy_gl_version();
    if (version < 45)
        return "OpenGL 4.5 needed (direct state access), the context has " +
               std::to_string(version / 10) + "." + std::to_string(version % 10);
    GLint maxSize = 0, maxLayers = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
    if (faceRes > maxSize)
        return "face_res " + std::to_string(faceRes) + " is over GL_MAX_TEXTURE_SIZE (" +
               std::to_string(maxSize) + ")";
    if (layers > maxLayers)
        return std::to_string(layers) +
               " texture-array layers are over GL_MAX_ARRAY_TEXTURE_LAYERS (" +
               std::to_string(maxLayers) + ")";
    return {};
}

gpu::TextureAllocator hostAllocator(const UnmanagedObjects& objects, const HostLayout& layout,
                                    const std::string& file) {
    if (objects.paramsBuffer != 0)
        if (const std::string mismatch =
                gpu::uniformBufferMismatch(objects.paramsBuffer, layout.paramsBytes);
            !mismatch.empty())
            throw Error(file, "paramsBuffer", mismatch);
    if (objects.textures.empty()) return gpu::createTexture;
    gpu::TextureAllocator allocate = gpu::hostTextureAllocator(objects.textures, file);
    for (const gpu::TextureSpec& spec : layout.textures)
        allocate(spec); // borrowed, so dropping it deletes nothing
    return allocate;
}

std::string hostGlslLibrary(const std::string& shader, const std::vector<std::string>& defines) {
    const gpu::ExpandedSource expanded =
        gpu::expandShader(gpu::ShaderSource::file(shader), defines);
    const std::size_t eol = expanded.text.find('\n');
    return eol == std::string::npos ? std::string() : expanded.text.substr(eol + 1);
}

void bindSampler(GLuint program, const char* name, GLuint unit, GLuint texture) {
    glBindTextureUnit(unit, texture);
    glProgramUniform1i(program, glGetUniformLocation(program, name), GLint(unit));
}

void setIntUniform(GLuint program, const char* name, int value) {
    glProgramUniform1i(program, glGetUniformLocation(program, name), value);
}

void bindUniformBlock(GLuint program, const char* block, GLuint binding) {
    const GLuint index = glGetUniformBlockIndex(program, block);
    if (index != GL_INVALID_INDEX) glUniformBlockBinding(program, index, binding);
}

void throwOnHostGlError(const std::string& file) {
    if (const GLenum error = glGetError(); error != GL_NO_ERROR)
        throw Error(file, "",
                    "OpenGL error " + std::to_string(error) + " creating the probe's objects");
}

} // namespace specula
