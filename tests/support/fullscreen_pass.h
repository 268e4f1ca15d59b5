#pragma once
// What the tests that run GLSL once per pixel share (a shared lookup or *.glsl.h header
// compiled as GLSL and compared with its C++ twin, one query per pixel): a full-screen
// triangle with no vertex buffer, and one draw of it into a render target, read back.
#include "engine/gpu/gl_objects.h"
#include "engine/gpu/render_target.h"
#include "engine/gpu/shader.h"
#include "engine/image/image.h"

#include <string>
#include <vector>

namespace specula::test {

// The vertex shader: one triangle covering the viewport, from gl_VertexID alone.
inline constexpr const char* kFullscreenTriangleVert = R"(
void main() {
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

// The program of fragment shader `frag` over the full-screen triangle; errors name its
// sources NAME.vert and NAME.frag.
inline gpu::Program buildFullscreenProgram(const std::string& name, const std::string& frag,
                                           const std::vector<std::string>& defines = {}) {
    return gpu::buildProgram(gpu::ShaderSource::text(name + ".vert", kFullscreenTriangleVert),
                             gpu::ShaderSource::text(name + ".frag", frag), defines);
}

// Clears `target`, draws the full-screen triangle into it with `prog` and reads it back (row 0
// at the top). `bind()` runs once the program is in use, before the draw: the pass's uniforms,
// textures and buffers.
template <typename Bind>
Image drawFullscreen(const gpu::RenderTarget& target, const gpu::Program& prog,
                     const gpu::VertexArray& vao, Bind bind) {
    target.bind();
    target.clear();
    prog.use();
    bind();
    glBindVertexArray(vao.id());
    glDisable(GL_DEPTH_TEST);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    return target.readback();
}

} // namespace specula::test
