#pragma once
// An OpenGL 4.5 core context, either headless (EGL, no window system: tests, the cooker,
// batch renders) or in a GLFW window (the interactive sandbox). GL entry points come from
// libepoxy, which dispatches to whichever of EGL or GLX made the current context.
//
// GL objects must be destroyed while their context is current: destroy every RAII wrapper
// (engine/gpu/gl_objects.h) before the GlContext that made them.
#include <memory>
#include <string>

struct GLFWwindow;

namespace specula::gpu {

class GlContext {
public:
    // Tries, in order: the EGL device platform (EGL_EXT_platform_device: every device until
    // one gives a 4.5 core context; NVIDIA's headless path), EGL_MESA_platform_surfaceless,
    // then eglGetDisplay(EGL_DEFAULT_DISPLAY). The context is current on return, with no
    // surface: draw into framebuffer objects. Throws specula::Error listing what was tried.
    static std::unique_ptr<GlContext> createHeadless();

    // A visible window with a 4.5 core context, current on return (works under Xvfb).
    static std::unique_ptr<GlContext> createWindow(int width, int height, const char* title);

    ~GlContext();
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    void makeCurrent();
    bool isHeadless() const { return window_ == nullptr; }
    GLFWwindow* window() const { return window_; } // null for a headless context
    void swapBuffers();                            // no-op for a headless context

    const std::string& renderer() const { return renderer_; } // GL_RENDERER
    const std::string& version() const { return version_; }   // GL_VERSION
    // How the context was obtained, e.g. "EGL device 0 (EGL_EXT_platform_device)".
    const std::string& origin() const { return origin_; }
    int majorVersion() const { return major_; }
    int minorVersion() const { return minor_; }

private:
    GlContext() = default;
    void queryInfo();

    // EGL handles are void* typedefs; kept opaque so this header needs no EGL include.
    void* eglDisplay_ = nullptr;
    void* eglContext_ = nullptr;
    GLFWwindow* window_ = nullptr;
    std::string renderer_, version_, origin_;
    int major_ = 0, minor_ = 0;
};

// True when env SPECULA_GL_DEBUG=1: contexts are created with the debug flag and
// KHR_debug messages are printed to stderr.
bool glDebugRequested();

} // namespace specula::gpu
