// Rows for the lookups the display's rounding reaches (pem_rounding_rows.h): the display's
// reflector point and direction are the rasteriser's interpolants, not the tracer's hit, and
// the distance geometry's search can end elsewhere for a difference of a few micrometres.
// The GL display itself is the reference: the twin on the shader's own inputs (OUTPUT 1, 2)
// against the traced targets, beside the cooker's fit on the tracer's inputs.
#include "assetcooker/lib/flavours/pem/pem_rounding_rows.h"
#include "assetcooker/lib/flavours/pem/pem_samples.h"
#include "assetcooker/lib/scene/probe_setup.h"
#include "components/reflection_probe/pem/pem_asset.h"
#include "components/reflection_probe/pem/pem_probe_cpu.h"
#include "components/reflection_probe/pem/system/pem_store.h"
#include "components/reflection_probe/pem/writer/pem_probe_writer.h"
#include "engine/context/context.h"
#include "pem_room.h"
#include "support/probe_room.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <unistd.h>

using namespace specula;
namespace fs = std::filesystem;

namespace {

constexpr int kWidth = 160, kHeight = 120;

double psnrOf(double squaredSum, long values) {
    return 10.0 * std::log10(double(values) / squaredSum);
}

PemCookSettings oneSample(int faceRes, float reach) {
    PemCookSettings s;
    s.samples = 1;
    s.faceRes = faceRes;
    s.imageWidth = kWidth;
    s.imageHeight = kHeight;
    s.localLayer = "off";
    s.roundingReach = reach;
    return s;
}

struct DisplayFit {
    double fit = 0;     // the cooker's, on the tracer's x and l
    double display = 0; // the same map on the rasteriser's x and l
    long pixels = 0;
};

// One sample of the room baked at t = 0 and drawn from that viewpoint.
DisplayFit displayAgainstFit(test::ProbeRoom& scene, test::RoomRenderer& renderer,
                             const PemCookSettings& s) {
    std::vector<PemSampleFit> fits;
    PemCookHooks hooks;
    hooks.fits = &fits;
    const PemAsset asset = cookPemAsset(scene.probeScene(), s, hooks);
    // A folder per bake: the store keeps an asset it loaded by its path.
    static int bake = 0;
    const fs::path dir =
        fs::temp_directory_path() /
        ("specula-pem-rounding-" + std::to_string(::getpid()) + "-" + std::to_string(bake++));
    writePemProbe(asset, dir.string(), scene.path());
    scene.setProbe((dir / "manifest.json").string(), PemProbe{0.f, false});
    const CameraView cam = walkOrbitCameraView(scene.probeScene(), kWidth, kHeight, 0.f);
    const Image pos = renderer.render(cam, 1);
    const Image dirs = renderer.render(cam, 2);
    PemSampleOptions o;
    o.supersample = 1;
    const PemSamples rays = tracePemSamples(scene.probeScene(), cam, asset.centre, o);
    const PemGpuProbe* synced = renderer.probes().store<PemStore>()->probe(scene.probeEntity());
    EXPECT_NE(synced, nullptr);
    const PemProbeCpu twin(*synced->asset, synced->params);
    double sum = 0;
    DisplayFit r;
    for (const PemSample& p : rays) {
        const int x = p.pixel % kWidth, y = p.pixel / kWidth;
        const glm::vec3 l(dirs.rgba(x, y));
        if (glm::length(l) < 0.5f) continue; // not drawn as reflector
        const glm::dvec3 d =
            glm::dvec3(twin.radiance(glm::vec3(pos.rgba(x, y)), l)) - glm::dvec3(p.target);
        sum += glm::dot(d, d);
        ++r.pixels;
    }
    r.fit = fits.at(0).psnrOn;
    r.display = psnrOf(sum, 3 * r.pixels);
    fs::remove_all(dir);
    return r;
}

} // namespace

// Room, 160x120, one viewpoint, 128² faces. Measured: without the rows the display draws
// 31.93 dB against the fit's 56.53 (two of 665 pixels read texels no row pinned); with them
// 55.34 against 56.58 (256²: 29.32 / 56.83 without, 53.11 / 56.83 with; 64²: 35.99 / 54.54,
// 54.44 / 54.55).
TEST(PemRoundingRows, DisplayDrawsWhatTheCookerFitted) {
    const auto context = gpu::GlContext::createHeadless();
    test::ProbeRoom scene;
    test::RoomRenderer renderer(scene, kWidth, kHeight);
    const DisplayFit without = displayAgainstFit(scene, renderer, oneSample(128, 0.f));
    const DisplayFit with =
        displayAgainstFit(scene, renderer, oneSample(128, PemCookSettings{}.roundingReach));
    std::printf("display / fit, dB: without rounding rows %.2f / %.2f, with %.2f / %.2f (%ld px)\n",
                without.display, without.fit, with.display, with.fit, with.pixels);
    ASSERT_GT(with.pixels, 500) << "the camera must see the reflectors";
    // The scene has rays on a knife edge: without the rows the display falls far below the fit.
    EXPECT_LT(without.display, without.fit - 10.0);
    // With them it draws what was fitted, and the fit itself loses nothing.
    EXPECT_GT(with.display, with.fit - 3.0);
    EXPECT_GT(with.fit, without.fit - 0.5);
}

// Random moves of the ray, no larger than the reach along any axis and mixing point and
// direction (the rows come from axis moves one at a time): where a move makes the lookup read
// other texels, the ray's own weights or one of its copies' hold those texels. Measured at
// 320x240, 64² faces, 16 moves a ray: 2,684 rays, 29 copies (1.1 %); of 42,944 moves 186
// read other texels, every one held by a copy (without the copies: none held).
TEST(PemRoundingRows, CopiesHoldWhereRandomMovesRead) {
    test::ProbeRoom scene;
    const float reach = PemCookSettings{}.roundingReach;
    PemCookSettings s = oneSample(64, reach);
    const PemAsset asset = cookPemAsset(scene.probeScene(), s, {});
    const PemMap& map = asset.samples.at(0).map;
    ASSERT_TRUE(map.distance);
    const PemLookupCpu lookup(map);
    PemSampleOptions o;
    o.supersample = 1;
    const PemSamples rays =
        tracePemSamples(scene.probeScene(), walkOrbitCameraView(scene.probeScene(), 320, 240, 0.f),
                        asset.centre, o);
    const PemSamples copies = pemRoundingCopies(lookup, rays, reach);
    // Copies follow their ray in order: find each ray's by matching target and position.
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-reach, reach);
    long moves = 0, shifted = 0, uncovered = 0;
    std::size_t next = 0;
    PemWeights w, own, other;
    auto shift = [](const PemWeights& a, const PemWeights& b) {
        float sum = 0.f;
        for (const auto& [t, wa] : a) {
            float wb = 0.f;
            for (const auto& [t2, w2] : b)
                if (t2 == t) wb = w2;
            sum += std::abs(wa - wb);
        }
        for (const auto& [t2, w2] : b)
            if (std::none_of(a.begin(), a.end(), [&](const auto& e) { return e.first == t2; }))
                sum += w2;
        return 0.5f * sum;
    };
    for (const PemSample& p : rays) {
        std::vector<PemWeights> held;
        lookup.weights(p.x, p.l, own, p.footprint());
        held.push_back(own);
        while (next < copies.size() && copies[next].target == p.target &&
               glm::length(copies[next].x - p.x) <= reach * 1.01f &&
               glm::length(copies[next].l - p.l) <= reach * 1.01f) {
            lookup.weights(copies[next].x, copies[next].l, other, p.footprint());
            held.push_back(other);
            ++next;
        }
        for (int m = 0; m < 16; ++m) {
            const glm::vec3 x = p.x + 0.5f * glm::vec3(u(rng), u(rng), u(rng));
            const glm::vec3 l = glm::normalize(p.l + 0.5f * glm::vec3(u(rng), u(rng), u(rng)));
            lookup.weights(x, l, w, p.footprint());
            ++moves;
            if (shift(w, own) <= kPemRoundingShift) continue;
            ++shifted;
            uncovered += std::none_of(held.begin(), held.end(), [&](const PemWeights& h) {
                return shift(w, h) <= kPemRoundingShift;
            });
        }
    }
    std::printf("%zu rays, %zu copies; %ld random moves: %ld read other texels, %ld of them "
                "texels no copy holds\n",
                rays.size(), copies.size(), moves, shifted, uncovered);
    EXPECT_EQ(next, copies.size()) << "every copy follows its ray";
    EXPECT_GT(shifted, 0) << "some moves within the reach must end the search elsewhere";
    EXPECT_LE(uncovered, shifted / 10);
}

// Box geometry has no search: no rows are added, whatever the reach.
TEST(PemRoundingRows, BoxGeometryAddsNone) {
    PemSamples samples = test::randomRays(400, 3, glm::vec3(0.f), 0.5f);
    for (PemSample& p : samples)
        p.target = test::wallRadiance(test::exitPoint(p.x, p.l, test::kRoomMin, test::kRoomMax));
    PemInferOptions o;
    o.faceRes = 8;
    o.boxMin = test::kRoomMin;
    o.boxMax = test::kRoomMax;
    o.roundingReach = 1e-3f;
    EXPECT_EQ(inferPemMap(samples, o).roundingRows, 0);
}
