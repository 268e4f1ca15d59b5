// Per-texel roughness on the GPU (issue 14): a rough reflector with a roughness map (the glTF
// metallic-roughness texture's G at TEXCOORD_0) compiles HAS_ROUGHNESS_MAP and reads its
// roughness per pixel, in the distance probe's, the distance level's and the light field's
// reflector shaders. Held against the CPU twins run at roughnessAt(factor, map, uv) with the
// uv the shader itself interpolated (OUTPUT 4); a map of ones (or of halves at twice the
// factor) draws the uniform roughness; and on the banded test asset (room_rough_bands.gltf)
// each band draws what its own uniform roughness draws, unlike the mean roughness.
#include "assetcooker/lib/flavours/lightfield/lightfield_bake.h"
#include "components/reflection_probe/distance/distance_level_cpu.h"
#include "components/reflection_probe/distance/system/distance_level_store.h"
#include "components/reflection_probe/lightfield/lightfield_probe_cpu.h"
#include "components/reflection_probe/lightfield/system/lightfield_store.h"
#include "components/reflection_probe/lightfield/writer/lightfield_probe_writer.h"
#include "components/reflection_probe/system/reflector_roughness.h"
#include "engine/image/ggx_albedo.h"
#include "probe_fixture.h"
#include "twin_agreement.h"
#include "two_room_level_gpu_fixture.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

using namespace specula;

namespace {

const std::string kBandsScene = SPECULA_SOURCE_DIR "/assets/room/room_rough_bands.gltf";
// The asset's bands, nominally (roughness_bands.png: G of 20 and 102 over 255, 4 texels wide
// across u); the tests draw with the values the loader decoded (bandLow, bandHigh).
constexpr float kLow = 20.f / 255.f, kHigh = 102.f / 255.f;

// A 4 x 4 map whose G is `g` everywhere (R and B 0: only G may be read).
std::shared_ptr<const Image> constantMap(float g) {
    auto map = std::make_shared<Image>(4, 4, 4);
    for (std::size_t i = 0; i < map->pixels.size(); i += 4)
        map->pixels[i + 1] = g;
    return map;
}

// Every reflector of `reg` at roughness factor `factor`, with `map` (null: uniform).
void setRoughness(ecs::Registry& reg, float factor, const std::shared_ptr<const Image>& map) {
    reg.view<Reflector>().each([&](ecs::Entity, Reflector& r) {
        r.roughness = factor;
        r.roughnessMap = map;
    });
}

bool drewMap(const std::vector<std::string>& names) {
    return std::any_of(names.begin(), names.end(), [](const std::string& n) {
        return n.find("roughness-map") != std::string::npos;
    });
}

// Per-pixel RGB distance between two frames over the pixels where `where(x, y)` holds.
struct FrameDiff {
    long n = 0;
    double worst = 0.0, sum = 0.0;
    double mean() const { return n ? sum / double(n) : 0.0; }
};
template <typename Where> FrameDiff frameDiff(const Image& a, const Image& b, Where where) {
    FrameDiff d;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            if (!where(x, y)) continue;
            const double e = glm::length(glm::vec3(a.rgba(x, y) - b.rgba(x, y)));
            ++d.n;
            d.sum += e;
            d.worst = std::max(d.worst, e);
        }
    return d;
}

// The shader's value at each mask pixel against its twin's, both at the roughness the twin
// reads there: roughnessAt(factor, map, uv) at the uv of the OUTPUT 4 frame. agreeByPixel
// compares them, handed each pixel's coordinates and roughness as its "position".
template <typename Shader, typename Twin>
test::PixelAgreement agreeAtPixelRoughness(const Image& mask, const Image& uv, float factor,
                                           const Image* map, Shader shader, Twin twin,
                                           double tolerance) {
    Image shaded(mask.width, mask.height, 3), at(mask.width, mask.height, 3);
    for (int y = 0; y < mask.height; ++y)
        for (int x = 0; x < mask.width; ++x) {
            if (mask.at(x, y)[0] < 0.5f) continue;
            const float r = roughnessAt(factor, map, glm::vec2(uv.rgba(x, y)));
            const glm::vec3 s = shader(x, y, r);
            std::copy(&s[0], &s[0] + 3, shaded.at(x, y));
            const glm::vec3 where(float(x), float(y), r);
            std::copy(&where[0], &where[0] + 3, at.at(x, y));
        }
    return test::agreeByPixel(
        shaded, at, at, mask,
        [&](glm::vec3 p, glm::vec3) { return glm::vec3(twin(int(p.x), int(p.y), p.z)); },
        tolerance);
}

// The room probe's suite (room.gltf cooked at 128^2 faces) plus the banded room drawn with it:
// room_rough_bands.gltf is room.gltf but for its reflectors' material (checked below), so
// the probe cooked from one is the probe of the other.
class RoughnessMapGpu : public test::RoomProbe {
protected:
    static void SetUpTestSuite() {
        RoomProbe::SetUpTestSuite();
        bands_ = new test::ProbeRoom(kBandsScene, test::kRoomSky);
        bandsRenderer_ = new test::RoomRenderer(*bands_, kWidth, kHeight);
    }
    static void TearDownTestSuite() {
        delete bandsRenderer_;
        delete bands_;
        RoomProbe::TearDownTestSuite();
    }
    void TearDown() override { setRoughness(scene_->registry(), 0.f, nullptr); }

    // The banded material's map, as the markup gave it to both reflectors.
    static std::shared_ptr<const Image> bandsMap() {
        return bands_->markup().reflectors.front().roughnessMap;
    }
    static float bandLow() { return roughnessMapMin(bandsMap().get()); }
    static float bandHigh() {
        float most = 0.f;
        for (std::size_t i = 1; i < bandsMap()->pixels.size(); i += 4)
            most = std::max(most, bandsMap()->pixels[i]);
        return most;
    }
    // The banded room's probe: distance (the room's cooked probe) or a light field.
    static void useBandsProbe(const DistanceProbe& p) { bands_->setProbe(manifest(), p); }

    static inline test::ProbeRoom* bands_ = nullptr;
    static inline test::RoomRenderer* bandsRenderer_ = nullptr;
};

// The markup reads the map from the material; the banded room's environment is the room's.
TEST_F(RoughnessMapGpu, BandedRoomReadsItsMapFromTheMaterial) {
    ASSERT_EQ(bands_->markup().reflectors.size(), 2u);
    for (const ReflectorMarkup& r : bands_->markup().reflectors) {
        EXPECT_EQ(r.roughness, 1.f) << r.node;
        ASSERT_TRUE(r.roughnessMap) << r.node;
        EXPECT_EQ(r.roughnessMap, bandsMap()) << r.node << ": one material, one map";
    }
    // The bands as the brief of the asset says: G depends on the column alone, 4 texels a band.
    const Image& map = *bandsMap();
    ASSERT_EQ(map.width, 32);
    ASSERT_EQ(map.height, 32);
    EXPECT_NEAR(bandLow(), kLow, 1e-6);
    EXPECT_NEAR(bandHigh(), kHigh, 1e-6);
    const float first = map.rgba(0, 0).g;
    ASSERT_TRUE(first == bandLow() || first == bandHigh()) << first;
    const float second = first == bandLow() ? bandHigh() : bandLow();
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x)
            ASSERT_EQ(map.rgba(x, y).g, (x / 4) % 2 == 0 ? first : second) << x << "," << y;
    EXPECT_EQ(bands_->probeCentre(), scene_->probeCentre());
    EXPECT_EQ(bands_->reflectorReach(), scene_->reflectorReach());
    const auto& a = bands_->markup().objects;
    const auto& b = scene_->markup().objects;
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].name, b[i].name);
        EXPECT_EQ(a[i].bounds.min, b[i].bounds.min) << a[i].name;
        EXPECT_EQ(a[i].bounds.max, b[i].bounds.max) << a[i].name;
    }
}

// The banded room through the distance probe: the shader's glossy colour over the GGX albedo
// E(|n.v|, r) at the pixel's roughness (|n.v| from OUTPUT 3) against the twin's glossyRadiance
// at that roughness, r = roughnessAt(1, bands, uv) with uv from OUTPUT 4. Same bounds as the
// uniform glossy test (distance_glossy_gpu_test): 99 % within 2e-3, mean under 5e-4. Measured
// (llvmpipe, 320 x 240, 2095 px, roughness 0.078 .. 0.400): envmap 100 % within, mean 4.7e-8,
// worst 2.8e-7; bisection 99.76 %, mean 2.2e-5, worst 8.9e-3 (a nearest distance fetch on a
// texel boundary ending the search a texel apart, as for the mirror shader).
TEST_F(RoughnessMapGpu, DistanceShaderMatchesTwinAtPerPixelRoughness) {
    const CameraView cam = bands_->camera(kWidth, kHeight);
    const Image mask = erodedMask(bands_->groundTruth(cam, true).mirrorMask);
    for (const DistanceMethod m : {DistanceMethod::Envmap, DistanceMethod::Bisection}) {
        useBandsProbe(probeFor(m));
        setRoughness(bands_->registry(), 1.f, bandsMap());
        const Image colour = bandsRenderer_->render(cam);
        EXPECT_TRUE(drewMap(bandsRenderer_->stats().permutations)) << toString(m);
        const Image pos = bandsRenderer_->render(cam, 1);
        const Image dir = bandsRenderer_->render(cam, 2);
        const Image nv = bandsRenderer_->render(cam, 3);
        const Image uv = bandsRenderer_->render(cam, 4);
        const ecs::Entity probe = bands_->probeEntity();
        const DistanceStore& store = *bandsRenderer_->probes().store<DistanceStore>();
        const CpuDistanceProbe twin(*store.asset(probe), *store.config(probe),
                                    store.glossyChain(probe));
        float least = 1.f, most = 0.f;
        const test::PixelAgreement a = agreeAtPixelRoughness(
            mask, uv, 1.f, bandsMap().get(),
            [&](int x, int y, float r) {
                least = std::min(least, r);
                most = std::max(most, r);
                return glm::vec3(colour.rgba(x, y)) / ggxAlbedo(nv.at(x, y)[0], r);
            },
            [&](int x, int y, float r) {
                return twin.glossyRadiance(glm::vec3(pos.rgba(x, y)), glm::vec3(dir.rgba(x, y)), r);
            },
            2e-3);
        std::printf("%-9s banded roughness %.3f..%.3f: twin vs GLSL %ld px, %.3f%% within 2e-3, "
                    "mean %.2e, worst %.2e, mean shader colour %.3f\n",
                    toString(m), least, most, a.n, 100.0 * a.share(), a.mean(), a.worst,
                    a.colourSum / double(std::max(a.n, 1L)));
        ASSERT_GT(a.n, 1000) << "the camera must see the reflectors";
        EXPECT_NEAR(least, bandLow(), 1e-6) << "the pixels read both bands";
        EXPECT_NEAR(most, bandHigh(), 1e-6);
        EXPECT_GT(a.share(), 0.99) << toString(m);
        EXPECT_LT(a.mean(), 5e-4) << toString(m);
        EXPECT_GT(a.colourSum / double(a.n), 0.01) << toString(m) << ": not black";
    }
}

// A map of ones at factor r, and a map of halves at factor 2r, draw the uniform roughness r
// (within float rounding of the bilinear weights; 1e-5 allowed):
// the map multiplies the factor. A mirror with a map reads no map (nor any roughness). Each
// distinct map is one texture upload, counted in the probes' bytes, dropped with its image.
// Measured: every pixel of the 320 x 240 frame bit-identical (worst 0) for envmap and
// bisection, both maps; the uniform frame is up to 0.91 / 1.01 from the mirror's.
TEST_F(RoughnessMapGpu, ConstantMapsDrawTheUniformRoughness) {
    const CameraView cam = scene_->camera(kWidth, kHeight);
    ReflectionProbeSystem& system = renderer_->probes();
    for (const DistanceMethod m : {DistanceMethod::Envmap, DistanceMethod::Bisection}) {
        useProbe(probeFor(m));
        setRoughness(scene_->registry(), 0.f, nullptr);
        const Image mirror = renderer_->render(cam);
        setRoughness(scene_->registry(), 0.f, bandsMap());
        const Image mirrorWithMap = renderer_->render(cam);
        EXPECT_FALSE(drewMap(renderer_->stats().permutations));
        EXPECT_EQ(frameDiff(mirror, mirrorWithMap, [](int, int) { return true; }).worst, 0.0);

        setRoughness(scene_->registry(), 0.2f, nullptr);
        const Image uniform = renderer_->render(cam);
        EXPECT_FALSE(drewMap(renderer_->stats().permutations));
        const std::size_t bytes = system.stats().probeGpuBytes;
        struct Case {
            float factor, g;
        };
        for (const Case c : {Case{0.2f, 1.f}, Case{0.4f, 0.5f}}) {
            const std::size_t uploads = system.stats().textureUploads;
            std::shared_ptr<const Image> map = constantMap(c.g);
            setRoughness(scene_->registry(), c.factor, map);
            const Image mapped = renderer_->render(cam);
            EXPECT_TRUE(drewMap(renderer_->stats().permutations));
            EXPECT_EQ(system.stats().textureUploads, uploads + 1) << "two reflectors, one map";
            EXPECT_EQ(system.stats().probeGpuBytes, bytes + 4 * 4 * 4) << "R32F 4 x 4";
            const FrameDiff d = frameDiff(uniform, mapped, [](int, int) { return true; });
            const FrameDiff moved = frameDiff(uniform, mirror, [](int, int) { return true; });
            std::printf("%-9s factor %.1f x map %.1f vs uniform 0.2: worst %.2e, mean %.2e over "
                        "%ld px (uniform vs mirror: worst %.3f)\n",
                        toString(m), c.factor, c.g, d.worst, d.mean(), d.n, moved.worst);
            EXPECT_LT(d.worst, 1e-5) << toString(m);
            EXPECT_GT(moved.worst, 0.05) << "the roughness shows";
            map.reset();
            setRoughness(scene_->registry(), 0.2f, nullptr);
            renderer_->render(cam);
            EXPECT_EQ(system.stats().probeGpuBytes, bytes) << "a freed map frees its texture";
        }
    }
}

// The banded room: pixels well inside a band (uv 3/4 texel or more from a band edge, so every
// bilinear tap reads that band) draw what that band's uniform roughness draws, and the two
// bands differ from the rendering at the map's mean roughness. The classes come from the uv
// alone (which band the texel column lies in, per the asset's layout checked above), and the
// twin's roughnessAt there must be that band's value. Measured (bisection): 615 low-band px
// and 670 high-band px bit-identical to the uniform 0.078 and 0.400 frames (worst 0), and
// 0.126 and 0.115 from the mean-roughness (0.239) frame on average; 810 px near band edges.
TEST_F(RoughnessMapGpu, EachBandDrawsItsOwnRoughness) {
    const CameraView cam = bands_->camera(kWidth, kHeight);
    const Image mask = erodedMask(bands_->groundTruth(cam, true).mirrorMask);
    useBandsProbe(probeFor(DistanceMethod::Bisection));
    auto render = [&](float factor, const std::shared_ptr<const Image>& map) {
        setRoughness(bands_->registry(), factor, map);
        return bandsRenderer_->render(cam);
    };
    const Image banded = render(1.f, bandsMap());
    const Image uv = bandsRenderer_->render(cam, 4);
    const Image low = render(bandLow(), nullptr);
    const Image high = render(bandHigh(), nullptr);
    const float meanRoughness = 0.5f * (bandLow() + bandHigh()); // equal bands
    const Image mean = render(meanRoughness, nullptr);

    // 0: outside; 1: inside the low band; 2: inside the high band; 3: near a band edge.
    const float first = bandsMap()->rgba(0, 0).g;
    std::vector<int> band(std::size_t(mask.width) * mask.height, 0);
    long twinMismatch = 0;
    for (int y = 0; y < mask.height; ++y)
        for (int x = 0; x < mask.width; ++x) {
            if (mask.at(x, y)[0] < 0.5f) continue;
            const glm::vec2 t = glm::vec2(uv.rgba(x, y));
            const float texel = 32.f * (t.x - std::floor(t.x)); // band edges at multiples of 4
            const float inBand = std::fmod(texel, 4.f);
            int& b = band[std::size_t(y) * mask.width + x];
            if (std::min(inBand, 4.f - inBand) < 0.75f) {
                b = 3;
                continue;
            }
            const bool firstBand = int(std::floor(texel / 4.f)) % 2 == 0;
            const float want = firstBand ? first : (first == bandLow() ? bandHigh() : bandLow());
            b = want == bandLow() ? 1 : 2;
            if (std::abs(roughnessAt(1.f, bandsMap().get(), t) - want) > 1e-6f) ++twinMismatch;
        }
    auto in = [&](int which) {
        return [&, which](int x, int y) { return band[std::size_t(y) * mask.width + x] == which; };
    };
    const FrameDiff lowSame = frameDiff(banded, low, in(1));
    const FrameDiff highSame = frameDiff(banded, high, in(2));
    const FrameDiff lowMean = frameDiff(banded, mean, in(1));
    const FrameDiff highMean = frameDiff(banded, mean, in(2));
    const FrameDiff edges = frameDiff(banded, mean, in(3));
    std::printf("bands: low %ld px (vs uniform %.3f: worst %.2e; vs mean %.3f: mean %.4f), high "
                "%ld px (vs uniform %.3f: worst %.2e; vs mean: mean %.4f), near edges %ld px\n",
                lowSame.n, bandLow(), lowSame.worst, meanRoughness, lowMean.mean(), highSame.n,
                bandHigh(), highSame.worst, highMean.mean(), edges.n);
    EXPECT_EQ(twinMismatch, 0) << "the twin reads each band's roughness inside it";
    ASSERT_GT(lowSame.n, 300);
    ASSERT_GT(highSame.n, 300);
    EXPECT_LT(lowSame.worst, 1e-5);
    EXPECT_LT(highSame.worst, 1e-5);
    EXPECT_GT(lowMean.mean(), 5e-3) << "the sharp band is not the mean";
    EXPECT_GT(highMean.mean(), 5e-3) << "the rough band is not the mean";
}

// The banded room through a light field (NUM 8, RES 64): the shader against its twin's
// reflectedRadiance (the glossy filter times E) at the pixel's roughness, with the bounds of
// the uniform light-field glossy test (99 % within 4e-3, mean under 1e-3); a map of ones draws
// the uniform roughness. Measured: ones vs uniform worst 0; banded 2095 px, 100 % within 4e-3,
// mean 4.4e-4, worst 1.2e-3 (the 8-bit bilinear weights of the sRGB atlas).
TEST_F(RoughnessMapGpu, LightFieldReadsTheMap) {
    LightFieldBakeOptions o;
    o.cellCentre = bands_->probeCentre();
    o.cellSize = bands_->cellSize();
    o.res = 64;
    o.sky = &bands_->sky();
    const std::string dir = dir_ + "/lightfield"; // removed with the suite's folder
    writeLightFieldProbe(bakeLightFieldProbe(bands_->registry(), bands_->markup(), o), dir,
                         bands_->path());
    bands_->setProbe(dir + "/manifest.json", LightFieldProbe{});
    const CameraView cam = bands_->camera(kWidth, kHeight);
    const Image mask = erodedMask(bands_->groundTruth(cam, true).mirrorMask);

    setRoughness(bands_->registry(), 0.3f, nullptr);
    const Image uniform = bandsRenderer_->render(cam);
    setRoughness(bands_->registry(), 0.3f, constantMap(1.f));
    const Image ones = bandsRenderer_->render(cam);
    EXPECT_TRUE(drewMap(bandsRenderer_->stats().permutations));
    const FrameDiff d = frameDiff(uniform, ones, [](int, int) { return true; });
    std::printf("light field: map of ones x 0.3 vs uniform 0.3: worst %.2e, mean %.2e\n", d.worst,
                d.mean());
    EXPECT_LT(d.worst, 1e-5);

    setRoughness(bands_->registry(), 1.f, bandsMap());
    const Image colour = bandsRenderer_->render(cam);
    EXPECT_TRUE(drewMap(bandsRenderer_->stats().permutations));
    const Image pos = bandsRenderer_->render(cam, 1);
    const Image dirs = bandsRenderer_->render(cam, 2);
    const Image normal = bandsRenderer_->render(cam, 3);
    const Image uv = bandsRenderer_->render(cam, 4);
    const CpuLightFieldProbe twin(
        *bandsRenderer_->probes().store<LightFieldStore>()->asset(bands_->probeEntity()));
    const test::PixelAgreement a = agreeAtPixelRoughness(
        mask, uv, 1.f, bandsMap().get(),
        [&](int x, int y, float) { return glm::vec3(colour.rgba(x, y)); },
        [&](int x, int y, float r) {
            return twin.reflectedRadiance(glm::vec3(pos.rgba(x, y)), glm::vec3(dirs.rgba(x, y)),
                                          glm::vec3(normal.rgba(x, y)), r);
        },
        4e-3);
    std::printf("light field banded: twin vs GLSL %ld px, %.3f%% within 4e-3, mean %.2e, worst "
                "%.2e\n",
                a.n, 100.0 * a.share(), a.mean(), a.worst);
    ASSERT_GT(a.n, 500);
    EXPECT_GT(a.share(), 0.99);
    EXPECT_LT(a.mean(), 1e-3);
    useBandsProbe(probeFor(DistanceMethod::Bisection));
}

class LevelRoughnessMapGpu : public test::TwoRoomLevelGpuTest {
protected:
    LevelRoughnessMapGpu() : TwoRoomLevelGpuTest("specula-level-roughness-map") {}
};

// A level of distance probes (the two rooms, the mirror in the doorway where both probes
// blend): a map of ones draws the uniform roughness; the banded map (the room's asset, read
// at the sphere's TEXCOORD_0) against the level twin at the pixel's roughness, with the
// uniform level test's bounds (99 % within 2e-3, mean under 1e-3). Measured (160 x 120,
// secant, default blend and K): ones vs uniform worst 0; banded 1938 px, 100 % within 2e-3,
// mean 4.7e-7, worst 5.1e-6.
TEST_F(LevelRoughnessMapGpu, LevelReadsTheMap) {
    constexpr int kW = 160, kH = 120;
    test::ProbeRoom room(test::kTwoRoomsScene, "");
    const auto [index, settings] = setUpSecantDoorway(room);
    const CameraView cam = doorwayCamera(kW, kH);
    const Image mask = erodedMask(room.groundTruth(cam, true).mirrorMask);
    test::RoomRenderer renderer(room, kW, kH);

    setRoughness(room.registry(), 0.3f, nullptr);
    const Image uniform = renderer.render(cam);
    setRoughness(room.registry(), 0.3f, constantMap(1.f));
    const Image ones = renderer.render(cam);
    EXPECT_TRUE(drewMap(renderer.stats().permutations));
    const FrameDiff d = frameDiff(uniform, ones, [](int, int) { return true; });
    std::printf("level: map of ones x 0.3 vs uniform 0.3: worst %.2e, mean %.2e\n", d.worst,
                d.mean());
    EXPECT_LT(d.worst, 1e-5);

    const std::shared_ptr<const Image> bands =
        test::ProbeRoom(kBandsScene, "").markup().reflectors.front().roughnessMap;
    ASSERT_TRUE(bands);
    setRoughness(room.registry(), 1.f, bands);
    const Image colour = renderer.render(cam);
    const Image pos = renderer.render(cam, 1);
    const Image dir = renderer.render(cam, 2);
    const Image nv = renderer.render(cam, 3);
    const Image uv = renderer.render(cam, 4);
    const CpuDistanceLevel twin(index, settings.lookup, true);
    float least = 1.f, most = 0.f;
    const test::PixelAgreement a = agreeAtPixelRoughness(
        mask, uv, 1.f, bands.get(),
        [&](int x, int y, float r) {
            least = std::min(least, r);
            most = std::max(most, r);
            return glm::vec3(colour.rgba(x, y)) / ggxAlbedo(nv.at(x, y)[0], r);
        },
        [&](int x, int y, float r) {
            return twin
                .radiance(glm::vec3(pos.rgba(x, y)), glm::vec3(dir.rgba(x, y)), settings.blend,
                          settings.k, r)
                .radiance;
        },
        2e-3);
    std::printf("level banded (roughness %.3f..%.3f): twin vs GLSL %ld px, %.3f%% within 2e-3, "
                "mean %.2e, worst %.2e\n",
                least, most, a.n, 100.0 * a.share(), a.mean(), a.worst);
    ASSERT_GT(a.n, 1000);
    EXPECT_NEAR(least, kLow, 1e-6);
    EXPECT_NEAR(most, kHigh, 1e-6);
    EXPECT_GT(a.share(), 0.99);
    EXPECT_LT(a.mean(), 1e-3);
}

} // namespace
