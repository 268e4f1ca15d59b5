// The PEM shader with MIP levels (PEM_MIP) against its CPU twin on the room, pixel by pixel:
// the level of detail the shader computes from its fine derivatives against the twin's from
// the quad twin (reflector_pixels.h), and, at the shader's own level of detail (OUTPUT 4), the
// twin's colour and the rendering matrix's row (weights times texels) against the GL colour
// of a random multi-level map, with box and with distance geometry.
#include "assetcooker/lib/scene/probe_setup.h"
#include "assetcooker/lib/scene/reflector_pixels.h"
#include "components/reflection_probe/pem/pem_asset.h"
#include "components/reflection_probe/pem/pem_probe_cpu.h"
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

constexpr int kWidth = 200, kHeight = 150;

struct Agreement {
    long n = 0, close = 0;
    double sum = 0, worst = 0;
    void add(double err, double bound) {
        ++n;
        close += err < bound;
        sum += err;
        worst = std::max(worst, err);
    }
    double fraction() const { return n ? double(close) / double(n) : 0.0; }
    double mean() const { return n ? sum / double(n) : 0.0; }
};

} // namespace

TEST(PemMipRuntime, ShaderMatchesTwinAndRenderingMatrixWithMips) {
    const auto context = gpu::GlContext::createHeadless();
    test::ProbeRoom scene;
    test::RoomRenderer renderer(scene, kWidth, kHeight);
    const glm::vec3 centre = scene.probeCentre();
    Aabb reflectors;
    for (const ReflectorMarkup& r : scene.markup().reflectors)
        for (ecs::Entity mesh : r.meshes)
            reflectors.extend(meshWorldBoundsConservative(scene.registry(), mesh));
    PemAsset header;
    header.centre = centre;
    header.faceRes = 64;
    header.mipLevels = 7;
    header.boxMin = reflectors.min - centre - 2.f;
    header.boxMax = reflectors.max - centre + 2.f;
    // Distance geometry too: a sphere of radius 3 about the centre, which the secant search
    // finds (its lookup runs the MIP read inside the search's loop).
    PemAsset distanceHeader = header;
    auto sphere = std::make_shared<PemDistanceGeometry>();
    sphere->faceRes = 8;
    sphere->distances.assign(std::size_t(PemMap::texelCount(8)), 3.f);
    sphere->dInf = 100.f;
    sphere->range = 10.f;
    sphere->tolerance = 0.01f;
    sphere->maxSteps = 20;
    distanceHeader.geometry = "distance";
    distanceHeader.distance = sphere;
    const fs::path dir =
        fs::temp_directory_path() / ("specula-pem-mip-gl-" + std::to_string(::getpid()));
    writePemProbe(test::randomPemAsset(header, 2, 29), (dir / "box").string(), scene.path());
    writePemProbe(test::randomPemAsset(distanceHeader, 2, 31), (dir / "distance").string(),
                  scene.path());

    const CameraView cam = scene.camera(kWidth, kHeight);
    const Image mask = erodedMask(scene.groundTruth(cam, true).mirrorMask);
    const GroundTruthTracer tracer(scene.registry(), groundTruthOptions(scene.probeScene(), true));
    const std::vector<ReflectorQuadPixel> quads =
        reflectorQuadPixels(scene.registry(), tracer, cam, mask);

    for (const char* geometry : {"box", "distance"})
        for (const PemProbe settings : {PemProbe{0.f, false}, PemProbe{0.25f, false}}) {
            scene.setProbe((dir / geometry / "manifest.json").string(), settings);
            const Image colour = renderer.render(cam, 0);
            const Image pos = renderer.render(cam, 1);
            const Image dirs = renderer.render(cam, 2);
            const Image lods = renderer.render(cam, 4);
            const auto& drawn = renderer.stats().permutations;
            const std::string variant =
                std::string(geometry) == "box" ? "pem+mip" : "pem-distance+mip";
            EXPECT_NE(std::find(drawn.begin(), drawn.end(), variant), drawn.end());
            const PemGpuProbe* synced =
                renderer.probes().store<PemStore>()->probe(scene.probeEntity());
            ASSERT_NE(synced, nullptr);
            const PemAsset& asset = *synced->asset;
            const PemProbeCpu twin(asset, synced->params);
            const PemMap& mapA = asset.samples[std::size_t(synced->params.layerA / 6)].map;
            const PemMap& mapB = asset.samples[std::size_t(synced->params.layerB / 6)].map;
            const float wb = synced->params.wb;
            Agreement atGpuLod, matrix, lod, full;
            std::vector<float> lodSeen;
            PemWeights w;
            for (const ReflectorQuadPixel& q : quads) {
                const int x = q.pixel.x, y = q.pixel.y;
                const glm::vec3 gpu(colour.rgba(x, y));
                const glm::vec3 px(pos.rgba(x, y)), l(dirs.rgba(x, y));
                PemFootprint atLod;
                atLod.lod = lods.at(x, y)[0];
                lodSeen.push_back(atLod.lod);
                // The lookup alone: the twin at the shader's level of detail, to float tolerance.
                atGpuLod.add(glm::length(twin.radiance(px, l, true, atLod) - gpu), 1e-5);
                // The rendering matrix's rows of both samples, blended as the shader blends them.
                glm::vec3 sum(0.f);
                for (const auto& [map, weight] :
                     {std::pair{&mapA, 1.f - wb}, std::pair{&mapB, wb}}) {
                    if (weight <= 0.f) continue;
                    PemLookupCpu(*map).weights(px, l, w, atLod);
                    for (const auto& [t, tw] : w)
                        sum += weight * tw * map->texels[std::size_t(t)];
                }
                matrix.add(glm::length(sum - gpu), 1e-5);
                // The level of detail from the quad twin's derivatives.
                const auto xOf = [&](const ReflectorPixel& p) { return p.position - centre; };
                const auto lOf = [](const ReflectorPixel& p) { return p.lhat; };
                PemFootprint f{q.dFdxFine(xOf), q.dFdyFine(xOf), q.dFdxFine(lOf), q.dFdyFine(lOf)};
                const float twinLod =
                    PemLookupCpu(mapA).lod(q.pixel.position - centre, q.pixel.lhat, f);
                const float clamped = std::clamp(twinLod, 0.f, float(asset.mipLevels - 1));
                lod.add(std::abs(clamped - std::clamp(atLod.lod, 0.f, float(asset.mipLevels - 1))),
                        0.02);
                full.add(glm::length(twin.radiance(px, l, true, f) - gpu), 2e-3);
            }
            std::sort(lodSeen.begin(), lodSeen.end());
            std::printf("pem+mip %s geometry, parameter %.2f over %ld px, GPU lod quartiles %.2f "
                        "%.2f %.2f: twin at "
                        "the GPU's lod %.3f%% within 1e-5 (worst %.2e); rendering matrix %.3f%% "
                        "within 1e-5 (worst %.2e); lod from the quad twin %.3f%% within 0.02 (mean "
                        "%.2e, worst %.2e); twin with the quad twin's lod %.3f%% within 2e-3 (mean "
                        "%.2e, worst %.2e)\n",
                        geometry, double(settings.parameter), atGpuLod.n,
                        lodSeen[lodSeen.size() / 4], lodSeen[lodSeen.size() / 2],
                        lodSeen[3 * lodSeen.size() / 4], 100.0 * atGpuLod.fraction(),
                        atGpuLod.worst, 100.0 * matrix.fraction(), matrix.worst,
                        100.0 * lod.fraction(), lod.mean(), lod.worst, 100.0 * full.fraction(),
                        full.mean(), full.worst);
            ASSERT_GT(atGpuLod.n, 500) << "the camera must see the reflectors";
            EXPECT_GT(lodSeen[lodSeen.size() / 2], 1.f) << "footprints must reach past level 0";
            EXPECT_GE(atGpuLod.fraction(), 0.999);
            EXPECT_GE(matrix.fraction(), 0.999);
            EXPECT_GE(lod.fraction(), 0.99);
            EXPECT_GE(full.fraction(), 0.98);
        }
    fs::remove_all(dir);
}
