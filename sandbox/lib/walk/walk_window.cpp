// The interactive walkthrough: a GLFW window (works under Xvfb), the frame drawn offscreen by
// FrameRenderer and shown as the background of a Dear ImGui panel that switches the method,
// d_e and the layer method, and shows the reflector-pass time and the current frame's error.
#include "assetcooker/lib/scene/walk_amplitude.h"
#include "sandbox/lib/walk/walk.h"

#include "engine/context/context.h"
#include "engine/core/error.h"
#include "engine/gpu/gl_objects.h"
#include "engine/gpu/timer.h"
#include "engine/image_io/compare.h"
#include "engine/image_io/image_io.h"
#include "sandbox/lib/render/frame_renderer.h"

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <unistd.h>

#include <glm/gtc/constants.hpp>

namespace fs = std::filesystem;

namespace specula {

namespace {

// Dear ImGui's global context, made and torn down with the window's lifetime.
struct ImGuiSession {
    explicit ImGuiSession(GLFWwindow* w) {
        IMGUI_CHECKVERSION();
        ImGui::CreateContext();
        ImGui::GetIO().IniFilename = nullptr; // no imgui.ini next to the user's files
        ImGui::StyleColorsDark();
        ImGui_ImplGlfw_InitForOpenGL(w, true);
        ImGui_ImplOpenGL3_Init("#version 450 core");
    }
    ~ImGuiSession() {
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
    ImGuiSession(const ImGuiSession&) = delete;
    ImGuiSession& operator=(const ImGuiSession&) = delete;
};

// The linear float frame, sRGB-encoded into an RGBA8 texture for display.
void uploadFrame(const Image& img, const gpu::Texture& tex, std::vector<std::uint8_t>& bytes) {
    bytes.resize(std::size_t(img.width) * img.height * 4);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const glm::vec4 c = img.rgba(x, y);
            std::uint8_t* p = &bytes[(std::size_t(y) * img.width + x) * 4];
            for (int k = 0; k < 3; ++k)
                p[k] = std::uint8_t(
                    std::lround(255.f * std::clamp(linearToSrgbValue(c[k]), 0.f, 1.f)));
            p[3] = 255;
        }
    glTextureSubImage2D(tex.id(), 0, 0, 0, img.width, img.height, GL_RGBA, GL_UNSIGNED_BYTE,
                        bytes.data());
}

// The distance flavour's panel, from its method table: the method, d_e, and in layered mode
// every object layer's method (the cooked plan's by default).
void distancePanel(DistanceProbe& p) {
    if (ImGui::BeginCombo("method", toString(p.method))) {
        for (const DistanceMethodInfo& row : kDistanceMethods)
            if (ImGui::Selectable(row.label.name, row.method == p.method)) p.method = row.method;
        ImGui::EndCombo();
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", info(p.method).label.help);
    ImGui::SliderFloat("d_e (m)", &p.errorTolerance, 0.001f, 0.3f, "%.4f",
                       ImGuiSliderFlags_Logarithmic);
    ImGui::BeginDisabled(p.method != DistanceMethod::Layered);
    const bool cooked = !info(p.layerMethod).perLayer;
    if (ImGui::BeginCombo("layers", cooked ? "cooked plan" : toString(p.layerMethod))) {
        if (ImGui::Selectable("cooked plan", cooked)) p.layerMethod = DistanceMethod::Envmap;
        for (const DistanceMethodInfo& row : kDistanceMethods)
            if (row.perLayer && ImGui::Selectable(row.label.name, row.method == p.layerMethod))
                p.layerMethod = row.method;
        ImGui::EndCombo();
    }
    ImGui::EndDisabled();
}

// The light-field flavour's panel: its one method, the focal disparity and the background.
void lightFieldPanel(LightFieldProbe& p) {
    ImGui::Text("method %s", kLightFieldMethod.name);
    ImGui::SliderFloat("disparity", &p.disparity, -1.f, 16.f,
                       p.disparity < 0.f ? "cooked" : "%.2f px");
    ImGui::Checkbox("background from light field", &p.background);
}

// The PEM flavour's panel: where on the cooked parameter axis the frame is (the path sets it
// while playing) and whether the nearest sample alone is drawn.
void pemPanel(PemProbe& p) {
    for (const PemMethodInfo& row : kPemMethods)
        if (row.nearest == p.nearest) ImGui::Text("method %s", row.label.name);
    ImGui::SliderFloat("parameter (viewpoint t)", &p.parameter, 0.f, 1.f, "%.3f");
    ImGui::Checkbox("nearest sample", &p.nearest);
}

// Shows the panel of the probe's flavour; true when its settings changed (written back).
template <typename Settings, typename Panel>
bool settingsPanel(ecs::Registry& registry, ecs::Entity probe, Panel panel) {
    Settings* current = registry.find<Settings>(probe);
    if (!current) return false;
    Settings edited = *current;
    panel(edited);
    if (edited == *current) return false;
    *current = edited;
    return true;
}

} // namespace

int runWalkWindow(const WalkOptions& o, std::ostream& out) {
    // A scene is baked into a temporary folder, removed however the walk ends.
    const fs::path bakeDir =
        fs::temp_directory_path() / ("specula-walk-" + std::to_string(::getpid()));
    struct RemoveOnExit {
        fs::path dir;
        ~RemoveOnExit() {
            std::error_code ec;
            fs::remove_all(dir, ec);
        }
    } cleanup{bakeDir};
    const ProbeSource src =
        resolveProbeSource(o.input, o.scene, o.sky, bakeDir.string(),
                           {o.faceRes, o.width, o.height, o.pemByReflector, o.path, o.cameraPath},
                           o.progress, walkSourceBake(o), &out, o.allowStale);
    const WalkMotion motion = walkMotion(src, o);
    auto context = gpu::GlContext::createWindow(o.width, o.height, "specula-sandbox walk");
    GLFWwindow* window = context->window();
    glfwSwapInterval(0);
    ReflectionScene scene(src.scenePath, src.skyPath);
    attachWalkProbe(scene, src, o);
    if (o.roughness) scene.setReflectorRoughness(*o.roughness);
    scene.setGlossyTruthSamples(o.glossySamples);
    out << "walk: " << context->renderer() << "; drag to orbit, wheel to zoom, WASD/QE move the "
        << "reflector, space plays the path, Esc quits\n";

    int frames = 0;
    {
        ImGuiSession imgui(window);
        FrameRenderer fr(scene, o.width, o.height);
        gpu::Texture display = gpu::Texture::create(GL_TEXTURE_2D);
        glTextureStorage2D(display.id(), 1, GL_RGBA8, o.width, o.height);
        glTextureParameteri(display.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(display.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        std::vector<std::uint8_t> bytes;

        float angle, distance, height;
        walkCameraOrbit(scene, angle, distance, height);
        glm::vec3 offset(0.f);
        // The slider's roughness: --roughness, else the roughest reflector's own.
        float roughness = o.roughness.value_or(0.f);
        if (!o.roughness)
            scene.registry().view<Reflector>().each(
                [&](ecs::Entity, Reflector& r) { roughness = std::max(roughness, r.roughness); });
        bool playing = o.frames > 0, showError = true;
        float t = 0.f;
        std::deque<double> passMs;
        std::string psnrText; // "none" when the view shows no reflector pixel
        std::uint64_t stateKey = 0, errorKey = ~0ull;
        auto lastChange = std::chrono::steady_clock::now();
        const float half = 0.5f * scene.cellSize();

        while (!glfwWindowShouldClose(window) && (o.frames <= 0 || frames < o.frames)) {
            glfwPollEvents();
            ImGui_ImplOpenGL3_NewFrame();
            ImGui_ImplGlfw_NewFrame();
            ImGui::NewFrame();
            const ImGuiIO& io = ImGui::GetIO();
            bool changed = false;
            if (!io.WantCaptureMouse) {
                if (ImGui::IsMouseDragging(ImGuiMouseButton_Left)) {
                    angle -= 0.01f * io.MouseDelta.x;
                    height = std::clamp(height + 0.01f * io.MouseDelta.y, -1.f, 3.f);
                    changed = true;
                }
                if (io.MouseWheel != 0.f) {
                    distance = std::clamp(distance * std::pow(0.9f, io.MouseWheel), 0.8f, 20.f);
                    changed = true;
                }
            }
            if (!io.WantCaptureKeyboard) {
                const float step = 0.6f * io.DeltaTime;
                const auto down = [&](int key) { return glfwGetKey(window, key) == GLFW_PRESS; };
                const glm::vec3 before = offset;
                if (down(GLFW_KEY_A) || down(GLFW_KEY_LEFT)) offset.x -= step;
                if (down(GLFW_KEY_D) || down(GLFW_KEY_RIGHT)) offset.x += step;
                if (down(GLFW_KEY_W) || down(GLFW_KEY_UP)) offset.z -= step;
                if (down(GLFW_KEY_S) || down(GLFW_KEY_DOWN)) offset.z += step;
                if (down(GLFW_KEY_E)) offset.y += step;
                if (down(GLFW_KEY_Q)) offset.y -= step;
                if (ImGui::IsKeyPressed(ImGuiKey_Space)) playing = !playing;
                if (ImGui::IsKeyPressed(ImGuiKey_Escape)) glfwSetWindowShouldClose(window, 1);
                offset = glm::clamp(offset, glm::vec3(-half), glm::vec3(half));
                changed |= offset != before;
            }
            if (playing) {
                t = std::fmod(t + 1.f / 120.f, 1.f);
                if (motion.moveReflectors)
                    offset = walkOffset(motion.path, t, scene.walkAmplitude());
                if (src.pem) { // the PEM's parameter follows t
                    setWalkParameter(scene, t);
                    if (motion.swingCamera) {
                        walkCameraOrbit(scene, angle, distance, height);
                        angle += 0.4f * std::sin(glm::two_pi<float>() * t);
                    }
                }
                changed = true;
            }

            // The panel.
            ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
            ImGui::Begin("Specula");
            const bool edited =
                settingsPanel<DistanceProbe>(scene.registry(), scene.probeEntity(),
                                             distancePanel) ||
                settingsPanel<LightFieldProbe>(scene.registry(), scene.probeEntity(),
                                               lightFieldPanel) ||
                settingsPanel<PemProbe>(scene.registry(), scene.probeEntity(), pemPanel);
            // Every reflector's roughness factor (a roughness map keeps multiplying it).
            const bool roughened = ImGui::SliderFloat("roughness", &roughness, 0.f, 1.f, "%.3f");
            if (roughened) scene.setReflectorRoughness(roughness);
            ImGui::Checkbox("play path", &playing);
            ImGui::SameLine();
            ImGui::Checkbox("error", &showError);
            const double medianPass =
                gpu::medianMs(std::vector<double>(passMs.begin(), passMs.end()));
            ImGui::Text("reflector pass %.3f ms (median of %zu)", medianPass, passMs.size());
            if (showError) {
                if (errorKey == ~0ull)
                    ImGui::TextDisabled("PSNR: waiting for the view to rest");
                else
                    ImGui::Text("PSNR vs ground truth %s%s", psnrText.c_str(),
                                errorKey == stateKey ? "" : " (stale)");
            }
            ImGui::Text("reflector offset %.2f %.2f %.2f", offset.x, offset.y, offset.z);
            ImGui::End();
            if (edited || roughened) {
                passMs.clear();
                changed = true;
            }
            if (changed) {
                ++stateKey;
                lastChange = std::chrono::steady_clock::now();
            }

            // A viewpoint PEM's maps hold the reflectors where they were baked.
            scene.setReflectorOffset(motion.moveReflectors ? offset : glm::vec3(0.f));
            // A PEM baked along the camera's animation is seen from that path at its parameter.
            const CameraView cam =
                walkFrameCamera(scene, motion, o.width, o.height, t, angle, distance, height);
            const Image img = fr.render(cam);
            if (frames > 0) { // the first timer result of a context can be garbage
                passMs.push_back(fr.passMs());
                if (passMs.size() > 31) passMs.pop_front();
            }
            // The error of the current view, traced once the view has rested for 0.3 s.
            if (showError && errorKey != stateKey &&
                std::chrono::steady_clock::now() - lastChange > std::chrono::milliseconds(300)) {
                // A PEM aims at the full multi-bounce truth, the other flavours at the
                // environment-only one.
                const GroundTruthImage gt = scene.groundTruth(cam, !src.pem);
                const Image mask = erodedMask(gt.mirrorMask);
                const ImageStats stats = compareImages(img, gt.color, &mask);
                psnrText = stats.hasPsnr ? formatPsnr(stats.psnr) + " dB"
                                         : "none (no reflector pixel in view)";
                errorKey = stateKey;
            }
            uploadFrame(img, display, bytes);

            int fbw = 0, fbh = 0;
            glfwGetFramebufferSize(window, &fbw, &fbh);
            ImGui::GetBackgroundDrawList()->AddImage(
                reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(display.id())),
                ImVec2(0, 0), ImVec2(io.DisplaySize.x, io.DisplaySize.y));
            ImGui::Render();
            glBindFramebuffer(GL_FRAMEBUFFER, 0);
            glViewport(0, 0, fbw, fbh);
            glClearColor(0.f, 0.f, 0.f, 1.f);
            glClear(GL_COLOR_BUFFER_BIT);
            ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
            context->swapBuffers();
            ++frames;
        }
    }
    out << "walk: " << frames << " frames shown\n";
    return 0;
}

} // namespace specula
