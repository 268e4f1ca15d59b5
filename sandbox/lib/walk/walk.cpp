#include "sandbox/lib/walk/walk.h"
#include "assetcooker/lib/scene/walk_amplitude.h"

#include "engine/context/context.h"
#include "engine/core/error.h"
#include "engine/core/file_write.h"
#include "engine/core/progress.h"
#include "engine/image_io/compare.h"
#include "engine/image_io/contact_sheet.h"
#include "engine/image_io/image_io.h"
#include "sandbox/lib/render/frame_renderer.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include <glm/gtc/constants.hpp>

namespace fs = std::filesystem;

namespace specula {

void walkCameraOrbit(const ReflectionScene& scene, float& angle, float& distance, float& height) {
    const CameraOrbit o = sceneCameraOrbit(scene.probeScene());
    angle = o.angle;
    distance = o.distance;
    height = o.height;
}

CameraView walkCamera(const ReflectionScene& scene, int width, int height, float angle,
                      float distance, float heightAbove) {
    return scene.orbitCamera(width, height, angle, distance, heightAbove);
}

CameraView walkCamera(const ReflectionScene& scene, int width, int height, float t) {
    return walkOrbitCameraView(scene.probeScene(), width, height, t);
}

void logAddedReflectors(const ReflectionScene& scene, int width, int height, std::ostream& out) {
    if (AddedReflectorsScope::current().empty()) return;
    std::size_t i = scene.markup().reflectors.size() - AddedReflectorsScope::current().size();
    for (const AddedReflector& r : AddedReflectorsScope::current())
        out << "added " << scene.markup().reflectors[i++].node << " (" << describeAddedReflector(r)
            << ")\n";
    const glm::vec3 eye = scene.camera(width, height).eye();
    out << "camera at " << eye.x << "," << eye.y << "," << eye.z << '\n';
}

SourceBake walkSourceBake(const WalkOptions& o) {
    if (o.method == kLightFieldMethod.name) return SourceBake::LightField;
    for (const PemMethodInfo& row : kPemMethods)
        if (o.method == row.label.name) return SourceBake::Pem;
    return SourceBake::Distance;
}

WalkMotion walkMotion(const ProbeSource& src, const WalkOptions& o) {
    if (src.pemByReflector) return {true, false, src.pemPath};
    if (o.cameraPath || src.pemCameraPath) return {false, false, o.path, true};
    if (!src.pem) return {true, true, o.path};
    return {false, true, o.path};
}

CameraView walkFrameCamera(const ReflectionScene& scene, const WalkMotion& motion, int width,
                           int height, float t, float angle, float distance, float heightAbove) {
    if (motion.cameraPath) return cameraPathView(scene.probeScene(), width, height, t);
    return walkCamera(scene, width, height, angle, distance, heightAbove);
}

void setWalkParameter(ReflectionScene& scene, float t) {
    if (PemProbe* p = scene.registry().find<PemProbe>(scene.probeEntity())) p->parameter = t;
}

ecs::Entity attachWalkProbe(ReflectionScene& scene, const ProbeSource& src, const WalkOptions& o) {
    if (src.lightField) return scene.attachProbe(src.manifest, LightFieldProbe{});
    if (src.pem) {
        PemProbe probe;
        for (const PemMethodInfo& row : kPemMethods)
            if (o.method == row.label.name) probe.nearest = row.nearest;
        return scene.attachProbe(src.manifest, probe);
    }
    const DistanceMethodInfo* row = findDistanceMethod(o.method);
    if (!row)
        throw Error(src.manifest, "flavour",
                    "method '" + o.method + "' needs a " + o.method +
                        " probe; this manifest is a distance probe (methods: " +
                        distanceMethodNames() + ")");
    DistanceProbe probe;
    probe.method = row->method;
    probe.errorTolerance = o.tolerance;
    probe.layerMethod = DistanceMethod::Envmap; // the cooked plan's choice per layer
    return scene.attachProbe(src.manifest, probe);
}

int runWalkHeadless(const WalkOptions& o, std::ostream& out) {
    const AddedReflectorsScope added(o.addedReflectors);
    fs::create_directories(o.outDir);
    const ProbeSource src = resolveProbeSource(
        o.input, o.scene, o.sky, (fs::path(o.outDir) / "probe").string(),
        SourceBakeSize{o.faceRes, o.width, o.height, o.pemByReflector, o.path, o.cameraPath},
        o.progress, walkSourceBake(o), &out, o.allowStale);
    if (src.baked) out << "baked " << src.manifest << " in " << src.bakeSeconds << " s\n";
    auto context = gpu::GlContext::createHeadless();
    ReflectionScene scene(src.scenePath, src.skyPath);
    attachWalkProbe(scene, src, o);
    logAddedReflectors(scene, o.width, o.height, out);
    if (o.roughness) {
        scene.setReflectorRoughness(*o.roughness);
        out << "every reflector at roughness " << *o.roughness
            << (o.compare && *o.roughness > 0.f
                    ? " (GGX truth, " + std::to_string(o.glossySamples) + " samples a pixel)"
                    : std::string())
            << '\n';
    }
    scene.setGlossyTruthSamples(o.glossySamples);
    if (o.roughness && *o.roughness > 0.f && src.pem)
        out << "note: a PEM draws its reflectors as mirrors (its maps hold no roughness); "
               "--compare measures them against the rough truth\n";

    std::ostringstream csv;
    csv << "frame,reflector_x,reflector_y,reflector_z,camera_angle_deg,pass_ms"
        << (o.compare ? ",psnr,psnr_full" : "") << '\n';
    const WalkMotion motion = walkMotion(src, o);
    const std::string pathName = motion.cameraPath ? kCameraPathName : toString(motion.path);
    if (src.pem && src.pemImageWidth > 0 &&
        (src.pemImageWidth != o.width || src.pemImageHeight != o.height))
        out << "note: the PEM was inferred for " << src.pemImageWidth << "x" << src.pemImageHeight
            << " frames; drawn at " << o.width << "x" << o.height
            << " every pixel is off the manifold (bake with --image-size " << o.width << "x"
            << o.height << ")\n";
    std::vector<Image> sheet;
    std::vector<std::string> labels;
    const int sheetEvery = std::max(1, (o.frames + 23) / 24); // at most 24 tiles
    {
        FrameRenderer fr(scene, o.width, o.height);
        // Warm-up: shader compile and upload; llvmpipe's first timer result can be garbage.
        fr.draw(walkCamera(scene, o.width, o.height, 0.f));
        float angle0, dist, h;
        walkCameraOrbit(scene, angle0, dist, h);
        std::optional<ProgressBar> bar;
        if (o.progress) bar.emplace("walk " + pathName);
        float previousAngle = 0.f;
        for (int i = 0; i < o.frames; ++i) {
            // A loop's frame `frames` would be frame 0 again; an open path ends on its last key.
            const float t = !motion.cameraPath ? float(i) / float(o.frames)
                            : o.frames > 1     ? float(i) / float(o.frames - 1)
                                               : 0.f;
            if (motion.moveReflectors)
                scene.setReflectorOffset(walkOffset(motion.path, t, scene.walkAmplitude()));
            setWalkParameter(scene, t);
            const float swing = motion.swingCamera ? DefaultViewpointRules::kWalkSwing *
                                                         std::sin(glm::two_pi<float>() * t)
                                                   : 0.f;
            float angle = angle0 + swing;
            const CameraView cam =
                walkFrameCamera(scene, motion, o.width, o.height, t, angle, dist, h);
            if (motion.cameraPath) {
                // The column holds the eye's angle about the probe, as the orbit's does,
                // unwrapped frame to frame: a path passing behind the probe does not jump 360°.
                const glm::vec3 e = cam.eye() - scene.probeCentre();
                const float raw = std::atan2(e.x, e.z);
                angle = i == 0 ? raw
                               : previousAngle +
                                     std::remainder(raw - previousAngle, glm::two_pi<float>());
                if (i == 0) angle0 = angle;
                previousAngle = angle;
            }
            const Image img = fr.render(cam);
            const double ms = fr.passMs();
            char name[32];
            std::snprintf(name, sizeof name, "frame_%04d.png", i);
            writeImage((fs::path(o.outDir) / name).string(), img);
            const glm::vec3 p = scene.reflectorPosition();
            csv << i << ',' << p.x << ',' << p.y << ',' << p.z << ','
                << glm::degrees(angle - angle0) << ',' << ms;
            if (o.compare) {
                // Against the environment-only truth (what a probe captured at a point can
                // hold) and the full multi-bounce one (what a PEM aims at).
                for (const bool environmentOnly : {true, false}) {
                    const GroundTruthImage gt = scene.groundTruth(cam, environmentOnly);
                    const Image mask = erodedMask(gt.mirrorMask);
                    // "none" when the frame has no reflector pixel or both are black (see
                    // ImageStats::hasPsnr): such a frame measures nothing and must not read
                    // as a perfect score.
                    csv << ',' << formatPsnr(compareImages(img, gt.color, &mask).psnr, 6);
                }
            }
            csv << '\n';
            if (i % sheetEvery == 0) {
                sheet.push_back(img);
                labels.push_back("frame " + std::to_string(i));
            }
            if (bar) bar->update(double(i + 1) / o.frames);
        }
    }
    writeFileAtomically((fs::path(o.outDir) / "frames.csv").string(), csv.str());
    writeImage(
        (fs::path(o.outDir) / "contact_sheet.png").string(),
        contactSheet(sheet, labels, std::min<int>(6, int(sheet.size())), std::min(o.width, 256)));
    // A light-field or PEM manifest draws with its flavour whatever --method says.
    const std::string drawn = src.lightField ? kLightFieldMethod.name
                              : src.pem && walkSourceBake(o) != SourceBake::Pem
                                  ? kPemMethods[0].label.name
                                  : o.method;
    out << "wrote " << o.frames << " frames (" << drawn << ", " << pathName
        << " path), contact_sheet.png and frames.csv to " << o.outDir << '\n';
    return 0;
}

} // namespace specula
