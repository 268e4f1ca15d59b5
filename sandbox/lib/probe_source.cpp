#include "probe_source.h"

#include "engine/core/error.h"
#include "sandbox/lib/lightfield_hook.h"

#include <cmath>
#include <filesystem>

#include <glm/gtc/constants.hpp>

namespace fs = std::filesystem;

namespace specula {

double bakeDistanceProbeInto(ReflectionScene& scene, const std::string& dir, int faceRes,
                             bool showProgress, bool planned, std::ostream* log) {
    DistanceCookSettings s;
    s.faceRes = faceRes;
    s.planned = s.recordPlan = planned;
    return cookSceneInto(scene, dir, s, showProgress, log).bakeSeconds;
}

CookResult cookSceneInto(ReflectionScene& scene, const std::string& dir, const CookFlavour& flavour,
                         bool showProgress, std::ostream* log) {
    CookOptions o;
    o.out = dir;
    o.flavour = flavour;
    o.progress = showProgress;
    return cookProbe(scene.probeScene(), o, log);
}

PemCookSettings sandboxPemSettings(int faceRes) {
    PemCookSettings s;
    s.samples = 8;
    s.faceRes = faceRes;
    s.supersample = 2;
    return s;
}

ProbeSource resolveProbeSource(const std::string& input,
                               const std::optional<std::string>& sceneOverride,
                               const std::optional<std::string>& skyOverride,
                               const std::string& bakeDir, int faceRes, bool showProgress,
                               SourceBake bake, std::ostream* log) {
    std::error_code ec; // a symlink loop or unreadable parent is an error naming the input
    if (!fs::exists(input, ec))
        throw Error(input, "", ec ? "cannot open: " + ec.message() : "no such file");
    ProbeSource src;
    const std::string ext = fs::path(input).extension().string();
    if (ext == ".json") {
        // One read of the manifest here; the asset (fields, files, checksums) is validated
        // when the probe system loads it, before anything is drawn.
        const CookedProbeFacts facts = readCookedProbeFacts(input);
        src.manifest = input;
        src.lightField = facts.flavour == "lightfield";
        src.pem = facts.flavour == "pem";
        if (sceneOverride) {
            src.scenePath = *sceneOverride;
        } else {
            if (facts.source.empty())
                throw Error(input, "source", "expected the scene's path (or give --scene)");
            const fs::path s = facts.source;
            const fs::path besideManifest = fs::path(input).parent_path() / s;
            src.scenePath = fs::exists(s) || s.is_absolute() || !fs::exists(besideManifest)
                                ? s.string()
                                : besideManifest.string();
        }
        if (!fs::exists(src.scenePath))
            throw Error(input, "source", "scene '" + src.scenePath + "' not found (give --scene)");
        src.skyPath = skyOverride                                            ? *skyOverride
                      : src.lightField || (src.pem && facts.skyFile.empty()) ? defaultSkyPath()
                                                                             : facts.skyFile;
        return src;
    }
    if (ext != ".gltf" && ext != ".glb")
        throw Error(input, "", "expected a scene (.gltf, .glb) or a probe manifest (.json)");
    src.scenePath = input;
    src.skyPath = skyOverride ? *skyOverride : defaultSkyPath();
    ReflectionScene scene(src.scenePath, src.skyPath);
    if (scene.markup().reflectors.empty())
        throw Error(input, "specula_reflector", "the scene has no reflector node");
    if (bake == SourceBake::LightField) {
        const LightFieldBake b = bakeLightField(scene, bakeDir, 16, 32, showProgress, log);
        src.bakeSeconds = b.seconds;
        src.lightField = true;
    } else if (bake == SourceBake::Pem) {
        src.bakeSeconds =
            cookSceneInto(scene, bakeDir, sandboxPemSettings(), showProgress, log).bakeSeconds;
        src.pem = true;
    } else {
        src.bakeSeconds = bakeDistanceProbeInto(scene, bakeDir, faceRes, showProgress, false, log);
    }
    src.manifest = (fs::path(bakeDir) / "manifest.json").string();
    src.baked = true;
    return src;
}

bool parseWalkPath(const std::string& s, WalkPath& out) {
    if (s == "orbit")
        out = WalkPath::Orbit;
    else if (s == "line")
        out = WalkPath::Line;
    else if (s == "figure8")
        out = WalkPath::Figure8;
    else
        return false;
    return true;
}

const char* toString(WalkPath p) {
    switch (p) {
    case WalkPath::Orbit:
        return "orbit";
    case WalkPath::Line:
        return "line";
    case WalkPath::Figure8:
        return "figure8";
    }
    return "?";
}

glm::vec3 walkOffset(WalkPath path, float t, float amplitude) {
    const float a = amplitude;
    const float w = glm::two_pi<float>() * t;
    switch (path) {
    case WalkPath::Orbit:
        return {a * std::sin(w), 0.25f * a * std::sin(2.f * w), a * std::cos(w)};
    case WalkPath::Line:
        return {a * std::sin(w), 0.f, 0.f};
    case WalkPath::Figure8:
        return {a * std::sin(w), 0.f, a * std::sin(2.f * w)};
    }
    return glm::vec3(0.f);
}

} // namespace specula
