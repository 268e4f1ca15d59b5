#include "sandbox/lib/flavours/distance/level_timing.h"

#include "assetcooker/lib/scene/probe_setup.h"
#include "components/reflection_probe/distance/distance_level.h"
#include "components/reflection_probe/level_index.h"
#include "engine/gpu/timer.h"
#include "sandbox/lib/render/frame_renderer.h"
#include "sandbox/lib/render/reflection_scene.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <optional>

namespace specula::sandbox {

namespace fs = std::filesystem;

namespace {

constexpr std::array<LevelBlend, 3> kBlends{LevelBlend::Nearest, LevelBlend::Engine,
                                            LevelBlend::Visibility};

} // namespace

// Both probes stay loaded and the reflectors are pointed at one or the
// other, so a switch uploads nothing but the level's parameter block; the configurations
// are timed in interleaved rounds (one frame each a round), so a change of load on the
// machine while timing falls on all of them alike.
std::vector<LevelPassTime> timeLevelPasses(ReflectionScene& rs, const std::string& levelDir,
                                           const DistanceProbe& lookup, const CameraView& camera,
                                           glm::vec3 reflector, float roughness,
                                           std::string& timer) {
    const std::string index = (fs::path(levelDir) / "level.json").string();
    const LevelIndex level = readLevelIndex(index);
    const auto nearest = std::min_element(level.probes.begin(), level.probes.end(),
                                          [&](const auto& a, const auto& b) {
                                              return glm::distance(a.volume.position, reflector) <
                                                     glm::distance(b.volume.position, reflector);
                                          });
    ecs::Registry& reg = rs.registry();
    float roughnessBefore = 0.f; // the scene's own, put back after (one for all reflectors)
    reg.view<Reflector>().each([&](ecs::Entity, Reflector& r) { roughnessBefore = r.roughness; });
    const ecs::Entity levelProbe = rs.attachProbe(index, DistanceLevel{lookup});
    DistanceProbe envmap = lookup;
    envmap.method = DistanceMethod::Envmap;
    const ecs::Entity envmapProbe = reg.create();
    reg.emplace<ReflectionProbe>(
        envmapProbe,
        ReflectionProbe{(fs::path(levelDir) / nearest->folder / "manifest.json").string()});
    reg.emplace<DistanceProbe>(envmapProbe, envmap);

    struct Config {
        LevelPassTime time;
        std::optional<DistanceLevel> level; // none: the envmap probe
        float roughness = 0.f;              // the reflectors' (the envmap's: mirrors)
        std::vector<double> samples;
    };
    std::vector<Config> configs{{{"envmap (one probe)", 1, 0, 0, 0}, std::nullopt, 0.f, {}}};
    for (const LevelBlend blend : kBlends)
        for (const int k : {1, 2, 4})
            if (blend != LevelBlend::Nearest || k == 1) // K does not change the nearest
                configs.push_back({{toString(blend), k, 0, 0, 0},
                                   DistanceLevel{lookup, blend, k},
                                   roughness,
                                   {}});
    // Rough: the mirror level's default blend too, so the glossy level's cost over the mirror
    // level's is a ratio of one run.
    if (roughness > 0.f)
        configs.push_back({{"visibility (mirror)", 4, 0, 0, 0},
                           DistanceLevel{lookup, LevelBlend::Visibility, 4},
                           0.f,
                           {}});
    FrameRenderer fr(rs, camera.width, camera.height);
    timer = fr.timerSource();
    const auto use = [&](const Config& c) {
        const ecs::Entity target = c.level ? levelProbe : envmapProbe;
        if (c.level) reg.get<DistanceLevel>(levelProbe) = *c.level;
        reg.view<Reflector>().each([&](ecs::Entity, Reflector& r) {
            r.probe = target;
            r.roughness = c.roughness;
        });
    };
    for (const Config& c : configs) { // warm-up: compile every variant, upload every probe
        use(c);
        fr.draw(camera);
    }
    constexpr int kRounds = 9;
    for (int round = 0; round < kRounds; ++round)
        for (Config& c : configs) {
            use(c);
            fr.draw(camera); // the parameter upload of a switch lands outside the timed frame
            fr.draw(camera);
            c.samples.push_back(fr.passMs());
        }
    std::vector<LevelPassTime> times;
    for (Config& c : configs) {
        c.time.ms = gpu::medianMs(c.samples);
        c.time.frames = int(c.samples.size());
        c.time.ratioToEnvmap =
            configs.front().time.ms > 0 ? c.time.ms / configs.front().time.ms : 0.0;
        times.push_back(c.time);
    }
    reg.destroy(envmapProbe);
    reg.view<Reflector>().each([&](ecs::Entity, Reflector& r) { r.roughness = roughnessBefore; });
    return times;
}

} // namespace specula::sandbox
