#include "sandbox/lib/flavours/distance/host_timing.h"

#include "components/reflection_probe/distance/distance_host_probe.h"
#include "engine/context/context.h"
#include "engine/core/error.h"
#include "engine/core/file_write.h"
#include "engine/gpu/shader.h"
#include "engine/gpu/timer.h"
#include "engine/image_io/compare.h"
#include "engine/image_io/contact_sheet.h"
#include "engine/image_io/image_io.h"
#include "sandbox/lib/render/frame_renderer.h"
#include "sandbox/lib/render/reflection_scene.h"
#include "sandbox/lib/walk/probe_source.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <ostream>
#include <sstream>

namespace specula::sandbox {

namespace fs = std::filesystem;

namespace {

constexpr const char* kReflectorVert = "components/reflection_probe/shaders/reflector.vert";

// What a host writes after Specula's library: the reflection at the pixel's roughness, times
// its own Schlick Fresnel (the sandbox's reflector pass applies the same).
constexpr const char* kHostFragment = R"(
uniform vec3 uEye;
uniform float uF0;        // < 0: a perfect mirror
uniform float uRoughness;
in vec3 vWorldPos;
in vec3 vNormal;
in vec2 vUv;
out vec4 fragColor;
void main() {
    vec3 v = normalize(vWorldPos - uEye);
    vec3 c = speculaReflect(vWorldPos, vNormal, v, uRoughness);
    if (uF0 >= 0.0) {
        float m = clamp(1.0 - abs(dot(normalize(vNormal), v)), 0.0, 1.0);
        c *= uF0 + (1.0 - uF0) * m * m * m * m * m;
    }
    fragColor = vec4(c, 1.0);
}
)";

// The host's frame: the environment as the sandbox draws it, then every reflector with the
// host's program, bound per draw as a host binds it.
class HostFrame {
public:
    HostFrame(ReflectionScene& rs, FrameRenderer& fr, const DistanceHostProbe& probe)
        : rs_(rs), fr_(fr), probe_(probe),
          program_(
              gpu::buildProgram(gpu::ShaderSource::file(kReflectorVert),
                                gpu::ShaderSource::text("host_reflector.frag",
                                                        probe.glslLibrary() + kHostFragment))) {
        const char* force = std::getenv("SPECULA_TIMER");
        wallClock_ = force ? std::string(force) == "wall" : softwareRasteriser();
    }

    // The reflector pass's time, with FrameRenderer::passMs's clock.
    double draw(const CameraView& camera) {
        ecs::Registry& reg = rs_.registry();
        glFinish();
        fr_.sceneRenderer().render(camera, fr_.target(),
                                   [&](ecs::Entity e) { return reg.has<Reflector>(e); });
        fr_.target().bind();
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glDisable(GL_CULL_FACE);
        const auto pass = [&] {
            reg.view<Reflector>().each([&](ecs::Entity e, Reflector& r) {
                program_.use();
                SceneRenderer::setCameraUniforms(program_, camera);
                probe_.bindTo(program_.id());
                program_.setUniform("uF0", r.fresnelF0);
                program_.setUniform("uRoughness", r.roughness > 0.f ? r.roughness : 0.f);
                fr_.sceneRenderer().drawEntity(e, program_);
            });
        };
        if (!wallClock_) return timer_.measure(pass);
        glFinish();
        const auto t0 = std::chrono::steady_clock::now();
        pass();
        glFinish();
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
            .count();
    }

private:
    ReflectionScene& rs_;
    FrameRenderer& fr_;
    const DistanceHostProbe& probe_;
    gpu::Program program_;
    gpu::GpuTimer timer_;
    bool wallClock_ = false;
};

HostTimingRow rowOf(const std::string& path, const std::vector<double>& samples) {
    const gpu::Quartiles q = gpu::quartilesMs(samples);
    int frames = 0;
    for (double s : samples)
        frames += std::isfinite(s);
    return {path, frames, q.q1, q.median, q.q3, 0.0};
}

} // namespace

HostTimingResult runHostTiming(const HostTimingOptions& o, std::ostream& log) {
    ReflectionScene rs(o.scene, o.sky);
    if (rs.markup().mirrorEntities.empty())
        throw Error(rs.path(), "specula_reflector", "the scene has no reflector to draw");
    fs::create_directories(o.out);
    std::string manifest = o.probe;
    if (manifest.empty()) {
        const std::string dir = (fs::path(o.out) / "probe").string();
        bakeDistanceProbeInto(rs, dir, o.faceRes, o.progress, false, &log);
        manifest = (fs::path(dir) / "manifest.json").string();
    }
    const auto context = gpu::GlContext::createHeadless();
    rs.attachProbe(manifest, DistanceProbe{}); // Planned: the method the cooker chose
    HostTimingResult result;
    bool rough = false;
    rs.registry().view<Reflector>().each([&](ecs::Entity, Reflector& r) {
        rough = rough || r.roughness > 0.f;
        ++result.reflectors;
    });
    const DistanceHostResult made = DistanceHostProbe::create(manifest, {.glossy = rough});
    if (!made) throw Error(made.error);

    const CameraView camera = rs.camera(o.width, o.height);
    FrameRenderer fr(rs, o.width, o.height);
    HostFrame host(rs, fr, *made.probe);
    result.timer = fr.timerSource();
    const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    result.renderer = renderer ? renderer : "?";

    const Image sandboxImage = fr.render(camera);
    host.draw(camera);
    const Image hostImage = fr.target().readback();
    const ImageStats stats = compareImages(hostImage, sandboxImage);
    result.psnrToSandbox = stats.psnr;
    result.maxDifference = stats.maxError;

    // Interleaved: a change of load while timing falls on both paths alike.
    std::vector<double> sandboxMs, hostMs;
    for (int i = 0; i < 2; ++i) { // warm-up
        fr.draw(camera);
        host.draw(camera);
    }
    for (int round = 0; round < o.rounds; ++round) {
        fr.draw(camera);
        sandboxMs.push_back(fr.passMs());
        hostMs.push_back(host.draw(camera));
    }
    result.rows = {rowOf("sandbox", sandboxMs), rowOf("host", hostMs)};
    for (HostTimingRow& r : result.rows)
        r.ratioToSandbox = r.medianMs / result.rows.front().medianMs;
    const HostTimingRow &s = result.rows[0], &h = result.rows[1];
    result.indistinguishable = h.q1Ms <= s.q3Ms && s.q1Ms <= h.q3Ms;

    std::ostringstream csv;
    csv << "path,frames,ms_q1,ms_median,ms_q3,ratio_to_sandbox,psnr_to_sandbox\n";
    for (const HostTimingRow& r : result.rows)
        csv << r.path << ',' << r.frames << ',' << r.q1Ms << ',' << r.medianMs << ',' << r.q3Ms
            << ',' << r.ratioToSandbox << ',' << formatPsnr(result.psnrToSandbox) << '\n';
    writeFileAtomically((fs::path(o.out) / "host.csv").string(), csv.str());
    Image difference = hostImage;
    const std::size_t channels = std::size_t(difference.channels);
    for (std::size_t i = 0; i < difference.pixels.size(); ++i)
        difference.pixels[i] = i % channels == 3
                                   ? 1.f // opaque
                                   : 10.f * std::abs(hostImage.pixels[i] - sandboxImage.pixels[i]);
    writeImage((fs::path(o.out) / "host.png").string(),
               hconcat({sandboxImage, hostImage, difference}, 4));

    log << "renderer: " << result.renderer << " (" << result.timer << ")\n"
        << result.reflectors << " reflectors, " << o.width << "x" << o.height << ", " << o.rounds
        << " interleaved rounds\n";
    for (const HostTimingRow& r : result.rows)
        log << "  " << r.path << ": median " << r.medianMs << " ms (IQR " << r.q1Ms << " .. "
            << r.q3Ms << "), ratio to sandbox " << r.ratioToSandbox << '\n';
    log << "host frame against the sandbox's: " << formatPsnr(result.psnrToSandbox)
        << " dB, max difference " << result.maxDifference << '\n';
    if (result.indistinguishable)
        log << "the two paths' interquartile ranges overlap: not told apart at this count\n";
    log << "-> " << o.out << "/host.csv, host.png\n";
    return result;
}

} // namespace specula::sandbox
