#include "engine/context/context.h"

#include "engine/core/error.h"
#include "engine/log/log.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <vector>

namespace specula::gpu {

bool glDebugRequested() {
    const char* v = std::getenv("SPECULA_GL_DEBUG");
    return v && std::strcmp(v, "1") == 0;
}

namespace {

std::mutex gMutex;
// EGL displays are per-platform singletons and eglTerminate is not reference counted, so
// two headless contexts on one device would otherwise tear each other down.
std::map<EGLDisplay, int> gDisplayUsers;
int gGlfwUsers = 0;
std::string gGlfwLastError;

const char* eglErrorName(EGLint e) {
    switch (e) {
    case EGL_SUCCESS:
        return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
        return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
        return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
        return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
        return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
        return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
        return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
        return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
        return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
        return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE:
        return "EGL_BAD_SURFACE";
    default:
        return "EGL error";
    }
}

std::string eglFailure(const char* call) {
    return std::string(call) + " failed (" + eglErrorName(eglGetError()) + ")";
}

void APIENTRY debugCallback(GLenum, GLenum type, GLuint id, GLenum severity, GLsizei,
                            const GLchar* message, const void*) {
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
    log().warn("[GL {}] {} (id {}, type {:#x})",
               severity == GL_DEBUG_SEVERITY_HIGH ? "high" : "medium/low", message, id, type);
}

void enableDebugOutput() {
    if (!glDebugRequested()) return;
    if (!epoxy_has_gl_extension("GL_KHR_debug") && epoxy_gl_version() < 43) return;
    glEnable(GL_DEBUG_OUTPUT);
    // Synchronous, so a breakpoint in the callback stops at the offending call.
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(debugCallback, nullptr);
}

void releaseDisplay(EGLDisplay dpy) {
    std::lock_guard lock(gMutex);
    auto it = gDisplayUsers.find(dpy);
    if (it == gDisplayUsers.end() || --it->second == 0) {
        eglTerminate(dpy);
        if (it != gDisplayUsers.end()) gDisplayUsers.erase(it);
    }
}

// Initialises `dpy` and makes a surfaceless 4.5 core context current on it. On failure
// appends why to `why` and leaves nothing initialised that it did not find initialised.
EGLContext tryDisplay(EGLDisplay dpy, std::string& why) {
    if (dpy == EGL_NO_DISPLAY) {
        why = "no display";
        return EGL_NO_CONTEXT;
    }
    EGLint major = 0, minor = 0;
    if (!eglInitialize(dpy, &major, &minor)) {
        why = eglFailure("eglInitialize");
        return EGL_NO_CONTEXT;
    }
    {
        std::lock_guard lock(gMutex);
        ++gDisplayUsers[dpy];
    }
    auto fail = [&](std::string msg) {
        why = std::move(msg);
        releaseDisplay(dpy);
        return EGL_NO_CONTEXT;
    };
    if (major < 1 || (major == 1 && minor < 4)) return fail("EGL 1.4 or later needed");
    if (!epoxy_has_egl_extension(dpy, "EGL_KHR_surfaceless_context"))
        return fail("no EGL_KHR_surfaceless_context");
    if (!epoxy_has_egl_extension(dpy, "EGL_KHR_create_context") && (major == 1 && minor < 5))
        return fail("no EGL_KHR_create_context");
    if (!eglBindAPI(EGL_OPENGL_API)) return fail(eglFailure("eglBindAPI(EGL_OPENGL_API)"));

    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!epoxy_has_egl_extension(dpy, "EGL_KHR_no_config_context")) {
        // Surface type 0 matches every config: no surface will ever be made.
        const EGLint attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0,
                                  EGL_NONE};
        EGLint count = 0;
        if (!eglChooseConfig(dpy, attribs, &config, 1, &count) || count < 1)
            return fail("no EGL config with EGL_OPENGL_BIT");
    }
    std::vector<EGLint> ctxAttribs = {
        EGL_CONTEXT_MAJOR_VERSION_KHR,       4,
        EGL_CONTEXT_MINOR_VERSION_KHR,       5,
        EGL_CONTEXT_OPENGL_PROFILE_MASK_KHR, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT_KHR};
    if (glDebugRequested()) {
        ctxAttribs.push_back(EGL_CONTEXT_FLAGS_KHR);
        ctxAttribs.push_back(EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR);
    }
    ctxAttribs.push_back(EGL_NONE);
    EGLContext ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, ctxAttribs.data());
    if (ctx == EGL_NO_CONTEXT) return fail(eglFailure("eglCreateContext(4.5 core)"));
    if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
        std::string msg = eglFailure("eglMakeCurrent(EGL_NO_SURFACE)");
        eglDestroyContext(dpy, ctx);
        return fail(msg);
    }
    return ctx;
}

} // namespace

std::unique_ptr<GlContext> GlContext::createHeadless() {
    std::vector<std::string> tried;
    auto finish = [&](EGLDisplay dpy, EGLContext ctx, std::string origin) {
        std::unique_ptr<GlContext> c(new GlContext());
        c->eglDisplay_ = dpy;
        c->eglContext_ = ctx;
        c->origin_ = std::move(origin);
        c->queryInfo();
        enableDebugOutput();
        return c;
    };

    const bool platformBase = epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_base");
    if (platformBase && epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_device") &&
        epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_enumeration")) {
        EGLint count = 0;
        eglQueryDevicesEXT(0, nullptr, &count);
        std::vector<EGLDeviceEXT> devices(std::size_t(count > 0 ? count : 0));
        if (count > 0) eglQueryDevicesEXT(count, devices.data(), &count);
        if (count <= 0) tried.push_back("EGL_EXT_platform_device: no devices");
        for (EGLint i = 0; i < count; ++i) {
            EGLDisplay dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
            std::string why;
            EGLContext ctx = tryDisplay(dpy, why);
            const std::string label = "EGL device " + std::to_string(i);
            if (ctx != EGL_NO_CONTEXT)
                return finish(dpy, ctx, label + " (EGL_EXT_platform_device)");
            tried.push_back("EGL_EXT_platform_device, " + label + ": " + why);
        }
    } else {
        tried.push_back("EGL_EXT_platform_device: extension not offered");
    }

    if (platformBase && epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless")) {
        EGLDisplay dpy =
            eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        std::string why;
        EGLContext ctx = tryDisplay(dpy, why);
        if (ctx != EGL_NO_CONTEXT) return finish(dpy, ctx, "EGL_MESA_platform_surfaceless");
        tried.push_back("EGL_MESA_platform_surfaceless: " + why);
    } else {
        tried.push_back("EGL_MESA_platform_surfaceless: extension not offered");
    }

    {
        EGLDisplay dpy = eglGetDisplay(EGL_DEFAULT_DISPLAY);
        std::string why;
        EGLContext ctx = tryDisplay(dpy, why);
        if (ctx != EGL_NO_CONTEXT) return finish(dpy, ctx, "eglGetDisplay(EGL_DEFAULT_DISPLAY)");
        tried.push_back("eglGetDisplay(EGL_DEFAULT_DISPLAY): " + why);
    }

    std::string msg = "no headless OpenGL 4.5 core context could be created; tried:";
    for (const auto& t : tried)
        msg += "\n  - " + t;
    msg += "\n(needs an EGL driver: NVIDIA's libEGL_nvidia or Mesa's libEGL_mesa, e.g. "
           "llvmpipe)";
    throw Error("EGL", "headless context", msg);
}

std::unique_ptr<GlContext> GlContext::createWindow(int width, int height, const char* title) {
    {
        std::lock_guard lock(gMutex);
        glfwSetErrorCallback([](int code, const char* desc) {
            gGlfwLastError = std::string(desc) + " (GLFW error " + std::to_string(code) + ")";
        });
        if (gGlfwUsers == 0 && !glfwInit()) {
            const char* display = std::getenv("DISPLAY");
            throw Error("GLFW", "window context",
                        "glfwInit failed: " + gGlfwLastError +
                            "; DISPLAY=" + (display ? display : "(unset)") +
                            " (run under a desktop session or xvfb-run)");
        }
        ++gGlfwUsers;
    }
    auto releaseGlfw = [] {
        std::lock_guard lock(gMutex);
        if (--gGlfwUsers == 0) glfwTerminate();
    };
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, glDebugRequested() ? GLFW_TRUE : GLFW_FALSE);
    GLFWwindow* window = glfwCreateWindow(width, height, title, nullptr, nullptr);
    if (!window) {
        const std::string why = gGlfwLastError;
        releaseGlfw();
        throw Error("GLFW", "window context",
                    "glfwCreateWindow(" + std::to_string(width) + "x" + std::to_string(height) +
                        ", OpenGL 4.5 core) failed: " + why);
    }
    glfwMakeContextCurrent(window);
    std::unique_ptr<GlContext> c(new GlContext());
    c->window_ = window;
    c->origin_ = "GLFW window";
    c->queryInfo();
    enableDebugOutput();
    return c;
}

GlContext::~GlContext() {
    if (window_) {
        glfwDestroyWindow(window_);
        std::lock_guard lock(gMutex);
        if (--gGlfwUsers == 0) glfwTerminate();
        return;
    }
    if (eglDisplay_) {
        auto dpy = static_cast<EGLDisplay>(eglDisplay_);
        if (eglGetCurrentContext() == static_cast<EGLContext>(eglContext_))
            eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(dpy, static_cast<EGLContext>(eglContext_));
        releaseDisplay(dpy);
    }
}

void GlContext::makeCurrent() {
    if (window_) {
        glfwMakeContextCurrent(window_);
        return;
    }
    if (!eglMakeCurrent(static_cast<EGLDisplay>(eglDisplay_), EGL_NO_SURFACE, EGL_NO_SURFACE,
                        static_cast<EGLContext>(eglContext_)))
        throw Error("EGL", "makeCurrent", eglFailure("eglMakeCurrent"));
}

void GlContext::swapBuffers() {
    if (window_) glfwSwapBuffers(window_);
}

void GlContext::queryInfo() {
    auto str = [](GLenum name) {
        const auto* s = reinterpret_cast<const char*>(glGetString(name));
        return std::string(s ? s : "");
    };
    renderer_ = str(GL_RENDERER);
    version_ = str(GL_VERSION);
    glGetIntegerv(GL_MAJOR_VERSION, &major_);
    glGetIntegerv(GL_MINOR_VERSION, &minor_);
}

} // namespace specula::gpu
