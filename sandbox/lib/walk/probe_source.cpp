#include "sandbox/lib/walk/probe_source.h"

#include "assetcooker/lib/scene/probe_inputs.h"
#include "components/reflection_probe/manifest_fields.h"

#include "engine/core/error.h"
#include "sandbox/lib/flavours/lightfield/lightfield_hook.h"

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

PemCookSettings sandboxPemSettings(SourceBakeSize size, int samples) {
    PemCookSettings s;
    s.samples = samples;
    s.faceRes = size.faceRes;
    s.imageWidth = size.width;
    s.imageHeight = size.height;
    s.supersample = 1;
    s.parameter = size.pemByReflector ? "reflector" : "viewpoint";
    s.path = size.pemByReflector ? toString(size.path)
             : size.cameraPath   ? kCameraPathName
                                 : "orbit";
    return s;
}

namespace {

// The parameter a PEM manifest's maps follow ("parameter_kind", "path"); the rest of the
// asset is validated when the probe system loads it.
void readPemParameter(const std::string& manifestPath, ProbeSource& src) {
    const ParsedManifest m = ParsedManifest::load(manifestPath);
    const ManifestFields f{m.path};
    src.pemByReflector = f.string(m.json, "parameter_kind", "") == "reflector";
    const std::string path = f.string(m.json, "path", "");
    src.pemCameraPath = path == kCameraPathName && !src.pemByReflector;
    if (!src.pemCameraPath && !parseWalkPath(path, src.pemPath))
        throw Error(manifestPath, "path",
                    "expected orbit, line, figure8 or camera (viewpoint only), got '" + path + "'");
    if (m.json.contains("image_size")) {
        const nlohmann::json& size = m.json["image_size"];
        if (size.is_array() && size.size() == 2 && size[0].is_number_integer() &&
            size[1].is_number_integer()) {
            src.pemImageWidth = size[0].get<int>();
            src.pemImageHeight = size[1].get<int>();
        }
    }
}

// The sky a PEM was baked under ("sky_source", resolved as "source" is: as written, else
// beside the manifest), for the ground truth it is compared with: "" a black sky (the
// cooker's default), the bundled field.jpg when the manifest does not say (older manifests).
std::string pemSky(const std::string& manifest, const CookedProbeFacts& facts) {
    if (!facts.skySourceGiven) return defaultSkyPath();
    if (facts.skySource.empty()) return "";
    const fs::path s = facts.skySource;
    const fs::path beside = fs::path(manifest).parent_path() / s;
    return fs::exists(s) || s.is_absolute() || !fs::exists(beside) ? s.string() : beside.string();
}

// A cooked probe walked in another scene than it was baked from measures nothing true: what
// differs, one line each on `log` (errors, or warnings with `allowStale`), then an Error
// unless allowed. The sky is compared when the walk lights the scene with a sky of its own.
void checkProbeFitsScene(const std::string& manifest, const CookedProbeFacts& facts,
                         const ProbeSource& src, bool compareSky, bool allowStale,
                         std::ostream* log) {
    if (!facts.inputs.recorded()) return; // cooked before probes recorded their inputs
    // The sky's checksum is its file's: the panorama is not decoded for it.
    const ProbeScene scene(src.scenePath, "");
    ProbeInputs now = sceneProbeInputs(scene, "");
    if (compareSky) now.sky = skyChecksum(src.skyPath);
    std::vector<std::string> stale;
    if (now.geometry != facts.inputs.geometry)
        stale.push_back(manifest + ": inputs.geometry: the probe was baked from " + facts.source +
                        " with other meshes, materials or reflectors than " + src.scenePath +
                        " has");
    if (compareSky && now.sky != facts.inputs.sky)
        stale.push_back(manifest + ": inputs.sky: the probe was baked under sky " +
                        facts.inputs.sky + ", the walk's sky is " + now.sky);
    for (const std::string& line : stale)
        if (log) *log << (allowStale ? "warning: " : "error: ") << line << '\n';
    if (!stale.empty() && !allowStale)
        throw Error(manifest, "inputs",
                    std::to_string(stale.size()) +
                        " input(s) differ from the scene walked (listed above): re-bake the "
                        "probe with specula-cook bake, or pass --allow-stale");
}

} // namespace

ProbeSource resolveProbeSource(const std::string& input,
                               const std::optional<std::string>& sceneOverride,
                               const std::optional<std::string>& skyOverride,
                               const std::string& bakeDir, SourceBakeSize size, bool showProgress,
                               SourceBake bake, std::ostream* log, bool allowStale) {
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
        if (src.pem) readPemParameter(input, src);
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
        src.skyPath = skyOverride      ? *skyOverride
                      : src.lightField ? defaultSkyPath()
                      : src.pem        ? pemSky(input, facts)
                                       : facts.skyFile;
        checkProbeFitsScene(input, facts, src, skyOverride.has_value(), allowStale, log);
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
            cookSceneInto(scene, bakeDir, sandboxPemSettings(size), showProgress, log).bakeSeconds;
        src.pem = true;
        src.pemByReflector = size.pemByReflector;
        src.pemPath = size.path;
        src.pemCameraPath = size.cameraPath && !size.pemByReflector;
        src.pemImageWidth = size.width;
        src.pemImageHeight = size.height;
    } else {
        src.bakeSeconds =
            bakeDistanceProbeInto(scene, bakeDir, size.faceRes, showProgress, false, log);
    }
    src.manifest = (fs::path(bakeDir) / "manifest.json").string();
    src.baked = true;
    return src;
}

} // namespace specula
