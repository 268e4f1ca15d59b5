// The two-layer PEM's shader (HAS_LOCAL_LAYER) against its CPU twin on the bowl room, pixel by
// pixel, and the hull flags it reads from its storage buffer by gl_PrimitiveID against the
// triangle Embree's primary ray hits (pemHullFlags of that reflector).
#include "assetcooker/lib/scene/probe_setup.h"
#include "components/reflection_probe/pem/pem_asset.h"
#include "components/reflection_probe/pem/pem_probe_cpu.h"
#include "components/reflection_probe/pem/system/pem_hull.h"
#include "components/reflection_probe/pem/system/pem_store.h"
#include "components/reflection_probe/pem/writer/pem_probe_writer.h"
#include "engine/context/context.h"
#include "engine/image_io/compare.h"
#include "engine/raytrace/ground_truth.h"
#include "engine/scene/mesh_bounds.h"
#include "pem_fixtures.h"
#include "support/probe_room.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <unistd.h>

using namespace specula;
namespace fs = std::filesystem;

namespace {

const std::string kBowlScene = SPECULA_SOURCE_DIR "/assets/bowl_room/bowl_room.gltf";
constexpr int kWidth = 200, kHeight = 150;

// Three samples of random distant (box) and local maps, the local sphere around the
// reflectors.
PemAsset randomLayered(glm::vec3 centre, const Aabb& reflectors) {
    PemAsset a;
    a.centre = centre;
    a.faceRes = 16;
    a.boxMin = reflectors.min - centre - 0.5f;
    a.boxMax = reflectors.max - centre + 0.5f;
    a.localLayer = true;
    a.localFaceRes = 12;
    a.localSphere = {0.5f * (reflectors.min + reflectors.max) - centre,
                     0.5f * glm::length(reflectors.max - reflectors.min)};
    return test::randomPemAsset(a, 3, 13);
}

} // namespace

TEST(PemLocalRuntime, ShaderMatchesTwinAndHullFlagsMatchEmbree) {
    const auto context = gpu::GlContext::createHeadless();
    test::ProbeRoom scene(kBowlScene, test::kRoomSky);
    test::RoomRenderer renderer(scene, kWidth, kHeight);
    const glm::vec3 centre = scene.probeCentre();
    Aabb box;
    for (const ReflectorMarkup& r : scene.markup().reflectors)
        for (ecs::Entity mesh : r.meshes)
            box.extend(meshWorldBoundsConservative(scene.registry(), mesh));
    const fs::path dir =
        fs::temp_directory_path() / ("specula-pem-local-gl-" + std::to_string(::getpid()));
    writePemProbe(randomLayered(centre, box), dir.string(), scene.path());
    const std::string manifest = (dir / "manifest.json").string();

    const CameraView cam = scene.camera(kWidth, kHeight);
    const Image mask = erodedMask(scene.groundTruth(cam, true).mirrorMask);
    const GroundTruthTracer tracer(scene.registry(), groundTruthOptions(scene.probeScene(), true));
    std::unordered_map<ecs::Entity, PemHullFlags> hulls;
    for (ecs::Entity e : scene.markup().mirrorEntities)
        hulls.emplace(e, pemHullFlags(scene.registry().get<Mesh>(e)));

    for (const PemProbe settings : {PemProbe{0.f, false}, PemProbe{0.5f, false}}) {
        scene.setProbe(manifest, settings);
        const Image colour = renderer.render(cam, 0);
        const Image pos = renderer.render(cam, 1);
        const Image dirs = renderer.render(cam, 2);
        const Image hull = renderer.render(cam, 3);
        const PemStore& store = *renderer.probes().store<PemStore>();
        const PemGpuProbe* synced = store.probe(scene.probeEntity());
        ASSERT_NE(synced, nullptr);
        const PemProbeCpu twin(*synced->asset, synced->params);
        long n = 0, close = 0, hullPx = 0, flagAgree = 0, flagPx = 0;
        double sum = 0, worst = 0;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                if (mask.at(x, y)[0] < 0.5f) continue;
                const bool onHull = hull.at(x, y)[0] > 0.5f;
                const glm::vec3 cpu =
                    twin.radiance(glm::vec3(pos.rgba(x, y)), glm::vec3(dirs.rgba(x, y)), onHull);
                const double err = glm::length(cpu - glm::vec3(colour.rgba(x, y)));
                ++n;
                hullPx += onHull;
                sum += err;
                worst = std::max(worst, err);
                close += err < 2e-3;
                // The flag of the triangle Embree's ray through the pixel centre hits.
                glm::vec3 o, d;
                cam.primaryRay(x, y, o, d);
                const std::optional<Hit> h = tracer.fullScene().intersect(o, d);
                if (!h || !hulls.contains(h->entity)) continue;
                ++flagPx;
                flagAgree += hulls.at(h->entity).flag(h->primitiveIndex, h->triangle) == onHull;
            }
        std::printf("pem+local parameter %.2f: twin vs GLSL over %ld px (%ld on the hull): %.3f%% "
                    "within 2e-3, mean %.2e, worst %.2e; hull flag = Embree's triangle's on "
                    "%.3f%% of %ld px\n",
                    double(settings.parameter), n, hullPx, 100.0 * double(close) / double(n),
                    sum / double(n), worst, 100.0 * double(flagAgree) / double(flagPx), flagPx);
        ASSERT_GT(n, 500) << "the camera must see the reflectors";
        EXPECT_GT(hullPx, n / 20) << "hull pixels (the sphere, the bowl's outside) are drawn";
        EXPECT_LT(hullPx, n - n / 20) << "the bowl's inside is drawn with its local layer";
        EXPECT_GE(double(close) / double(n), 0.995);
        EXPECT_LT(sum / double(n), 5e-4);
        EXPECT_GE(double(flagAgree) / double(flagPx), 0.99);
    }
    const auto& drawn = renderer.stats().permutations;
    EXPECT_NE(std::find(drawn.begin(), drawn.end(), "pem+local"), drawn.end());
    fs::remove_all(dir);
}
