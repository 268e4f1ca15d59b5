// The smallest host of Specula's runtime: its own context (a GLFW window, or EGL with
// --headless), its own shader and "entities" (a mirror sphere and a rough disc, ray cast per
// pixel), and a cooked distance probe drawn through DistanceHostProbe. Lines marked SPECULA
// are all the integration a host writes.
//   minimal MANIFEST [--headless] [--out image.pfm|image.ppm] [--size W H]
#include "components/reflection_probe/distance/distance_host_probe.h" // SPECULA

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLFW/glfw3.h>
#include <epoxy/gl.h>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace {

const char* kVertex = R"(#version 450 core
out vec2 ndc;
void main() {
    ndc = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2) * 2.0 - 1.0;
    gl_Position = vec4(ndc, 0.0, 1.0);
})";

// The host's fragment shader, after "#version" and Specula's library.
const char* kFragment = R"(
uniform mat4 uInvViewProj;
uniform vec3 uEye;
uniform vec4 uSphere;     // centre, radius: a mirror
uniform vec4 uDisc;       // centre, radius: a horizontal rough disc
uniform float uRoughness; // the disc's
in vec2 ndc;
out vec4 colour;
void main() {
    vec4 far = uInvViewProj * vec4(ndc, 1.0, 1.0);
    vec3 d = normalize(far.xyz / far.w - uEye);
    vec3 o = uEye - uSphere.xyz;
    float b = dot(o, d), c = dot(o, o) - uSphere.w * uSphere.w, h = b * b - c;
    float tSphere = h >= 0.0 ? -b - sqrt(h) : -1.0;
    float tDisc = (uDisc.y - uEye.y) / d.y;
    vec3 q = uEye + tDisc * d - uDisc.xyz;
    if (!(tDisc > 0.0 && dot(q, q) <= uDisc.w * uDisc.w)) tDisc = -1.0;
    if (tSphere > 0.0 && (tDisc < 0.0 || tSphere < tDisc)) {
        vec3 p = uEye + tSphere * d;
        colour = vec4(speculaReflect(p, p - uSphere.xyz, d, 0.0), 1.0); // SPECULA
    } else if (tDisc > 0.0) {
        colour = vec4(speculaReflect(uEye + tDisc * d, vec3(0, 1, 0), d, uRoughness), 1.0); // SPECULA
    } else {
        colour = vec4(0.0);
    }
})";

GLuint compile(GLenum stage, const std::string& text) {
    const GLuint s = glCreateShader(stage);
    const char* src = text.c_str();
    glShaderSource(s, 1, &src, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096];
        glGetShaderInfoLog(s, sizeof log, nullptr, log);
        std::fprintf(stderr, "minimal: shader: %s\n", log);
    }
    return s;
}

bool headlessContext() {
    EGLDisplay dpy =
        eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, nullptr, nullptr)) {
        dpy = eglGetDisplay(EGL_DEFAULT_DISPLAY);
        if (!eglInitialize(dpy, nullptr, nullptr)) return false;
    }
    eglBindAPI(EGL_OPENGL_API);
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                              4,
                              EGL_CONTEXT_MINOR_VERSION,
                              5,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK,
                              EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                              EGL_NONE};
    EGLContext ctx = eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
    return ctx != EGL_NO_CONTEXT && eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx);
}

// PFM (float RGB, rows bottom to top as GL reads them) or PPM (8-bit, clamped, flipped).
bool writeImage(const std::string& path, int w, int h, const std::vector<float>& rgba) {
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) return false;
    const bool pfm = path.size() > 4 && path.substr(path.size() - 4) == ".pfm";
    std::fprintf(f, pfm ? "PF\n%d %d\n-1\n" : "P6\n%d %d\n255\n", w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                const float v = rgba[(std::size_t(pfm ? y : h - 1 - y) * w + x) * 4 + c];
                const int byte = int(255.f * std::min(1.f, std::max(0.f, v)) + 0.5f);
                pfm ? std::fwrite(&v, 4, 1, f) : std::size_t(std::fputc(byte, f));
            }
    return std::fclose(f) == 0;
}

} // namespace

int main(int argc, char** argv) {
    if (argc < 2 || !std::strcmp(argv[1], "--help")) {
        std::printf(
            "usage: minimal MANIFEST [--headless] [--out image.pfm|image.ppm] [--size W H]\n");
        return argc < 2 ? 2 : 0;
    }
    bool headless = false;
    std::string out;
    int w = 320, h = 240;
    for (int i = 2; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--headless"))
            headless = true;
        else if (!std::strcmp(argv[i], "--out") && i + 1 < argc)
            out = argv[++i];
        else if (!std::strcmp(argv[i], "--size") && i + 2 < argc)
            w = std::atoi(argv[++i]), h = std::atoi(argv[++i]);
    }
    GLFWwindow* window = nullptr;
    if (headless) {
        if (!headlessContext())
            return std::fprintf(stderr, "minimal: no EGL OpenGL 4.5 context\n"), 1;
    } else {
        if (!glfwInit()) return 1;
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        if (!(window = glfwCreateWindow(w, h, "Specula minimal", nullptr, nullptr))) return 1;
        glfwMakeContextCurrent(window);
    }

    specula::DistanceHostResult made =
        specula::DistanceHostProbe::create(argv[1], {.glossy = true});              // SPECULA
    if (!made) return std::fprintf(stderr, "minimal: %s\n", made.error.c_str()), 1; // SPECULA
    const specula::DistanceHostProbe& probe = *made.probe;                          // SPECULA

    const GLuint program = glCreateProgram();
    glAttachShader(program, compile(GL_VERTEX_SHADER, kVertex));
    const std::string fragment = "#version 450 core\n" + probe.glslLibrary() + kFragment; // SPECULA
    glAttachShader(program, compile(GL_FRAGMENT_SHADER, fragment));
    glLinkProgram(program);
    GLint linked = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &linked);
    if (!linked) return std::fprintf(stderr, "minimal: the program does not link\n"), 1;

    // The scene around the probe: a mirror sphere at its centre, a rough disc below it.
    const glm::vec3 c = probe.centre(); // SPECULA
    const glm::vec3 eye = c + glm::vec3(0.f, 0.45f, 1.6f);
    const glm::mat4 viewProj =
        glm::perspective(glm::radians(50.f), float(w) / float(h), 0.05f, 100.f) *
        glm::lookAt(eye, c - glm::vec3(0.f, 0.15f, 0.f), glm::vec3(0.f, 1.f, 0.f));
    glUseProgram(program);
    glUniformMatrix4fv(glGetUniformLocation(program, "uInvViewProj"), 1, GL_FALSE,
                       &glm::inverse(viewProj)[0][0]);
    glUniform3fv(glGetUniformLocation(program, "uEye"), 1, &eye[0]);
    glUniform4f(glGetUniformLocation(program, "uSphere"), c.x, c.y, c.z, 0.3f);
    glUniform4f(glGetUniformLocation(program, "uDisc"), c.x, c.y - 0.45f, c.z, 0.9f);
    glUniform1f(glGetUniformLocation(program, "uRoughness"), 0.3f);

    GLuint vao = 0, target = 0, fbo = 0;
    glCreateVertexArrays(1, &vao);
    glCreateTextures(GL_TEXTURE_2D, 1, &target);
    glTextureStorage2D(target, 1, GL_RGBA32F, w, h);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, target, 0);
    do {
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glViewport(0, 0, w, h);
        glUseProgram(program);
        probe.bindTo(program); // SPECULA
        glBindVertexArray(vao);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        if (window) {
            glBlitNamedFramebuffer(fbo, 0, 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
            glfwSwapBuffers(window);
            glfwPollEvents();
        }
    } while (window && !glfwWindowShouldClose(window));

    int status = 0;
    if (!out.empty()) {
        std::vector<float> rgba(std::size_t(w) * h * 4);
        glGetTextureImage(target, 0, GL_RGBA, GL_FLOAT, GLsizei(rgba.size() * 4), rgba.data());
        if (!writeImage(out, w, h, rgba)) {
            std::fprintf(stderr, "minimal: cannot write %s\n", out.c_str());
            status = 1;
        }
    }
    made.probe.reset(); // SPECULA: its GL objects go while the context is current
    if (window) glfwTerminate();
    return status;
}
