// Glossy reflections of distance probes on the GPU (issue 14): the HAS_GLOSSY shader against
// its CPU twin (CpuDistanceProbe::glossySample, the same shared code over the same chain), the
// shared seam-free chain sampler in GLSL against sampleChain, and the permutation: a rough
// reflector compiles glossy in, a mirror draws the mirror shader exactly.
#include "components/reflection_probe/distance/distance_glossy_chain.h"
#include "components/reflection_probe/distance/distance_textures.h"
#include "engine/gpu/render_target.h"
#include "probe_fixture.h"
#include "support/fullscreen_pass.h"
#include "twin_agreement.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

using namespace specula;

namespace {

class GlossyGpu : public test::RoomProbe {
protected:
    void TearDown() override { setRoughness(0.f); }

    // Every reflector of the room (the sphere and the torus) at this perceptual roughness.
    static void setRoughness(float r) {
        scene_->registry().view<Reflector>().each(
            [&](ecs::Entity, Reflector& c) { c.roughness = r; });
    }
    static bool anyGlossy(const std::vector<std::string>& names) {
        return std::any_of(names.begin(), names.end(), [](const std::string& n) {
            return n.find("glossy") != std::string::npos;
        });
    }
    static std::string joined(const std::vector<std::string>& names) {
        std::string s;
        for (const std::string& n : names)
            s += (s.empty() ? "" : ", ") + n;
        return s;
    }
    static bool samePixels(const Image& a, const Image& b) {
        return a.width == b.width && a.height == b.height && a.pixels.size() == b.pixels.size() &&
               std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
    }
};

constexpr float kRoughness = 0.2f;

} // namespace

// The twin runs on the exact inputs the shader used (probe-local position and reflected
// direction, read back as float32) with the chain the store uploaded, so the two agree to
// float precision except where a nearest distance fetch on a texel boundary flips between GPU
// and CPU and ends the search a texel apart (as for the mirror shader, distance_gpu_test).
// No pixel reads the sky panorama here: a glossy ray that hits nothing reads the chain.
TEST_F(GlossyGpu, ShaderMatchesCpuTwinPerPixel) {
    const CameraView cam = scene_->camera(kWidth, kHeight);
    const Image mask = erodedMask(scene_->groundTruth(cam, true).mirrorMask);
    const DistanceMethod methods[] = {DistanceMethod::Envmap,    DistanceMethod::BoxProj,
                                      DistanceMethod::Bisection, DistanceMethod::Secant,
                                      DistanceMethod::AvgDist,   DistanceMethod::Layered};
    for (const DistanceMethod m : methods) {
        useProbe(probeFor(m));
        setRoughness(0.f);
        const Image mirror = renderer_->render(cam);
        setRoughness(kRoughness);
        const Image colour = renderer_->render(cam);
        const std::vector<std::string> drawn = renderer_->stats().permutations;
        const Image pos = renderer_->render(cam, 1);
        const Image dir = renderer_->render(cam, 2);
        const Image lighting =
            test::withoutGgxAlbedo(colour, renderer_->render(cam, 3), mask, kRoughness);

        const ecs::Entity probe = scene_->probeEntity();
        const DistanceStore& store = *renderer_->probes().store<DistanceStore>();
        const std::shared_ptr<const CubeChain> chain = store.glossyChain(probe);
        ASSERT_TRUE(chain) << "a rough reflector drew: the store made the chain";
        const CpuDistanceProbe twin(*store.asset(probe), *store.config(probe), chain);
        const test::PixelAgreement a = test::agreeByPixel(
            lighting, pos, dir, mask,
            [&](glm::vec3 x, glm::vec3 l) { return twin.glossyRadiance(x, l, kRoughness); }, 2e-3);
        // How far glossy moves the image from the mirror's: the comparison is not vacuous.
        double fromMirror = 0.0;
        long n = 0;
        for (int y = 0; y < mask.height; ++y)
            for (int x = 0; x < mask.width; ++x)
                if (mask.at(x, y)[0] >= 0.5f) {
                    fromMirror += glm::length(glm::vec3(colour.rgba(x, y) - mirror.rgba(x, y)));
                    ++n;
                }
        fromMirror /= double(std::max(n, 1L));
        std::printf("%-9s glossy r %.1f twin vs GLSL: %ld px, %.3f%% within 2e-3, mean %.2e, "
                    "worst %.2e; mean shader colour %.3f; mean change from the mirror %.4f "
                    "[%s]\n",
                    toString(m), kRoughness, a.n, 100.0 * a.share(), a.mean(), a.worst,
                    a.colourSum / double(std::max(a.n, 1L)), fromMirror, joined(drawn).c_str());
        ASSERT_GT(a.n, 1000) << "the camera must see the reflectors";
        EXPECT_GT(a.share(), 0.99) << toString(m);
        EXPECT_LT(a.mean(), 5e-4) << toString(m);
        EXPECT_GT(a.colourSum / double(a.n), 0.01) << toString(m) << ": not black";
        EXPECT_GT(fromMirror, 5e-3) << toString(m) << ": the glossy path ran";
        EXPECT_TRUE(anyGlossy(drawn)) << toString(m);
    }
}

// Roughness 0 is a mirror: the HAS_GLOSSY variant is not used and the image is the mirror
// shader's, bit for bit, before and after a rough frame. A permutation names "glossy" only
// while a reflector is rough, and per reflector: a rough torus beside a mirror sphere draws
// both variants.
TEST_F(GlossyGpu, RoughnessZeroDrawsTheMirrorShader) {
    const CameraView cam = scene_->camera(kWidth, kHeight);
    for (const DistanceMethod m : {DistanceMethod::Envmap, DistanceMethod::BoxProj,
                                   DistanceMethod::Bisection, DistanceMethod::Secant}) {
        useProbe(probeFor(m));
        setRoughness(0.f);
        const Image before = renderer_->render(cam);
        const std::vector<std::string> mirrorNames = renderer_->stats().permutations;
        setRoughness(kRoughness);
        const Image rough = renderer_->render(cam);
        const std::vector<std::string> roughNames = renderer_->stats().permutations;
        setRoughness(0.f);
        const Image after = renderer_->render(cam);
        const std::vector<std::string> afterNames = renderer_->stats().permutations;
        std::printf("%-9s r 0: [%s]; r %.1f: [%s]\n", toString(m), joined(mirrorNames).c_str(),
                    kRoughness, joined(roughNames).c_str());
        EXPECT_FALSE(anyGlossy(mirrorNames)) << joined(mirrorNames);
        EXPECT_FALSE(anyGlossy(afterNames)) << joined(afterNames);
        EXPECT_EQ(afterNames, mirrorNames);
        ASSERT_FALSE(roughNames.empty());
        for (const std::string& name : roughNames)
            EXPECT_NE(name.find("glossy"), std::string::npos) << name;
        EXPECT_TRUE(samePixels(before, after)) << toString(m);
        EXPECT_FALSE(samePixels(before, rough)) << toString(m);

        // One rough reflector (the torus: no Fresnel), one mirror (the sphere: Fresnel f0 1).
        int roughOnes = 0;
        scene_->registry().view<Reflector>().each([&](ecs::Entity, Reflector& c) {
            c.roughness = c.fresnelF0 < 0.f ? kRoughness : 0.f;
            roughOnes += c.roughness > 0.f ? 1 : 0;
        });
        ASSERT_EQ(roughOnes, 1);
        renderer_->render(cam);
        const std::vector<std::string> mixed = renderer_->stats().permutations;
        std::printf("%-9s torus rough, sphere mirror: [%s]\n", toString(m), joined(mixed).c_str());
        const std::string method = toString(m);
        EXPECT_EQ(std::count(mixed.begin(), mixed.end(), method + "+glossy"), 1) << joined(mixed);
        EXPECT_EQ(std::count(mixed.begin(), mixed.end(), method + "+fresnel"), 1) << joined(mixed);
        EXPECT_EQ(mixed.size(), 2u) << joined(mixed);
    }
}

// The chain is made by sync when a reflector turns rough (so the timed reflector pass only
// draws), once per probe, counted as a texture upload and in the probes' GPU bytes; it is the
// chain the CPU twins would make (glossyChainOf: the room was baked without glossy levels, so
// the composite prefiltered with the default options).
TEST_F(GlossyGpu, ChainIsMadeInSyncOutsideTheTimedPass) {
    // A copy of the cooked probe: a new asset, so the store starts without a chain.
    const std::string copy = dir_ + "-copy";
    std::filesystem::remove_all(copy);
    std::filesystem::copy(dir_, copy, std::filesystem::copy_options::recursive);
    useProbe(probeFor(DistanceMethod::Bisection), copy + "/manifest.json");
    ReflectionProbeSystem& system = renderer_->probes();
    const DistanceStore& store = *system.store<DistanceStore>();
    setRoughness(0.f);
    system.sync(scene_->registry());
    const ecs::Entity probe = scene_->probeEntity();
    EXPECT_FALSE(store.glossyChain(probe)) << "no rough reflector: no chain";
    const std::size_t uploads = system.stats().textureUploads;
    const std::size_t bytes = system.stats().probeGpuBytes;

    setRoughness(kRoughness);
    system.sync(scene_->registry());
    const std::shared_ptr<const CubeChain> chain = store.glossyChain(probe);
    ASSERT_TRUE(chain);
    EXPECT_EQ(system.stats().textureUploads, uploads + 1);
    EXPECT_EQ(system.stats().probeGpuBytes, bytes + chainArrayBytes(*chain));
    renderer_->render(scene_->camera(kWidth, kHeight));
    EXPECT_EQ(system.stats().textureUploads, uploads + 1) << "nothing more uploaded";
    EXPECT_EQ(store.glossyChain(probe), chain);

    const CubeChain want = glossyChainOf(*store.asset(probe));
    ASSERT_EQ(chain->levels.size(), want.levels.size());
    EXPECT_EQ(chain->levels.size(), std::size_t(GgxPrefilterOptions{}.levels));
    for (std::size_t i = 0; i < want.levels.size(); ++i)
        for (int f = 0; f < 6; ++f)
            EXPECT_EQ(chain->levels[i][std::size_t(f)].pixels,
                      want.levels[i][std::size_t(f)].pixels)
                << "level " << i << " face " << f;
    std::printf("chain: %zu levels, %zu GPU bytes (every probe texture before it: %zu)\n",
                chain->levels.size(), chainArrayBytes(*chain), bytes);

    setRoughness(0.f);
    useProbe(probeFor(DistanceMethod::Bisection));
    system.sync(scene_->registry());
    std::filesystem::remove_all(copy);
}

// A probe baked with its glossy levels (--glossy on): the store and the twins read the
// cooked levels (glossyChainOf), which are the chain the lookup would otherwise prefilter
// itself, bit for bit; the shader still matches its twin on them.
TEST_F(GlossyGpu, CookedGlossyLevelsAreTheChainTheShaderReads) {
    const std::string cooked = dir_ + "-glossy";
    std::filesystem::remove_all(cooked);
    DistanceCookSettings settings;
    settings.faceRes = 64;
    settings.planned = settings.recordPlan = false;
    settings.glossy = GlossyBake::On;
    CookOptions o;
    o.out = cooked;
    o.flavour = settings;
    o.progress = false;
    cookProbe(scene_->probeScene(), o, nullptr);
    const DistanceProbeAsset asset = readDistanceProbe(cooked + "/manifest.json");
    ASSERT_EQ(asset.glossyLevels.size(), std::size_t(GgxPrefilterOptions{}.levels - 1));
    const CubeChain fromAsset = glossyChainOf(asset);
    DistanceProbeAsset bare = asset;
    bare.glossyLevels.clear();
    const CubeChain prefiltered = glossyChainOf(bare);
    ASSERT_EQ(fromAsset.levels.size(), prefiltered.levels.size());
    for (std::size_t i = 0; i < prefiltered.levels.size(); ++i) {
        EXPECT_EQ(fromAsset.roughness[i], prefiltered.roughness[i]) << i;
        for (int f = 0; f < 6; ++f)
            EXPECT_EQ(fromAsset.levels[i][std::size_t(f)].pixels,
                      prefiltered.levels[i][std::size_t(f)].pixels)
                << "level " << i << " face " << f;
    }

    const CameraView cam = scene_->camera(kWidth, kHeight);
    const Image mask = erodedMask(scene_->groundTruth(cam, true).mirrorMask);
    useProbe(probeFor(DistanceMethod::Bisection), cooked + "/manifest.json");
    setRoughness(kRoughness);
    const Image colour = renderer_->render(cam);
    const Image pos = renderer_->render(cam, 1);
    const Image dir = renderer_->render(cam, 2);
    const Image lighting =
        test::withoutGgxAlbedo(colour, renderer_->render(cam, 3), mask, kRoughness);
    const DistanceStore& store = *renderer_->probes().store<DistanceStore>();
    const ecs::Entity probe = scene_->probeEntity();
    const std::shared_ptr<const CubeChain> chain = store.glossyChain(probe);
    ASSERT_TRUE(chain);
    ASSERT_EQ(chain->levels.size(), fromAsset.levels.size());
    for (std::size_t i = 1; i < chain->levels.size(); ++i)
        EXPECT_EQ(chain->levels[i][0].pixels, asset.glossyLevels[i - 1][0].pixels) << i;
    const CpuDistanceProbe twin(*store.asset(probe), *store.config(probe), chain);
    const test::PixelAgreement a = test::agreeByPixel(
        lighting, pos, dir, mask,
        [&](glm::vec3 x, glm::vec3 l) { return twin.glossyRadiance(x, l, kRoughness); }, 2e-3);
    std::printf("cooked levels (64^2): twin vs GLSL %ld px, %.3f%% within 2e-3, mean %.2e\n", a.n,
                100.0 * a.share(), a.mean());
    EXPECT_GT(a.share(), 0.99);
    EXPECT_LT(a.mean(), 5e-4);

    setRoughness(0.f);
    useProbe(probeFor(DistanceMethod::Bisection));
    renderer_->probes().sync(scene_->registry());
    std::filesystem::remove_all(cooked);
}

namespace {

// A cube chain of n x n faces and `levels` levels with distinct, position-dependent texels
// (so any misread texel, face or level shows), in the prefilter's sizes: max(1, n >> i).
CubeChain patternChain(int n, int levels) {
    CubeChain chain;
    for (int i = 0; i < levels; ++i) {
        const int m = std::max(1, n >> std::min(i, 30));
        CubeFaces faces;
        for (int f = 0; f < 6; ++f) {
            faces[std::size_t(f)] = Image(m, m, 4);
            for (int y = 0; y < m; ++y)
                for (int x = 0; x < m; ++x) {
                    float* p = faces[std::size_t(f)].at(x, y);
                    p[0] = float(f + 1) + 0.37f * float(x) / float(m);
                    p[1] = float(i + 1) + 0.61f * float(y) / float(m);
                    p[2] = std::sin(float(3 * x + 5 * y + 7 * f + 11 * i));
                    p[3] = 1.f;
                }
        }
        chain.levels.push_back(std::move(faces));
        chain.roughness.push_back(ggxChainRoughness(i, levels));
    }
    return chain;
}

} // namespace

// The shared sampler (engine/math/cube_chain_sample.glsl.h) compiled as GLSL over the chain
// textures the store uploads (level 0 in the cube array, levels 1.. in uploadChainArray's
// mipmapped array, read by shaders/distance_glossy_gpu.glsl) against sampleChain on the CPU:
// random directions and levels, plus directions right on face edges and cube corners (where
// taps read across faces and the corner mean), levels out of range and NaN. Face sizes: a
// power of two, one that is not (6: 6, 3, 1, ...) and chains longer than the mip pyramid
// (4 and 6: the last levels are 1 x 1 and share the last mip).
TEST_F(GlossyGpu, ChainSamplerInGlslMatchesSampleChain) {
    static constexpr const char* kFrag = R"(
#include "engine/core/glsl_device.glsl"
#include "components/reflection_probe/distance/shaders/distance_params.glsl.h"
uniform sampler2DArray uLayers;
layout(std140, binding = kDistanceParamsBinding) uniform DistanceParamsUniforms {
    DistanceParamsBlock uDistance;
};
#include "components/reflection_probe/distance/shaders/distance_glossy_gpu.glsl"
#include "engine/math/cube_chain_sample.glsl.h"
uniform sampler2D uQueries; // xyz direction, w level
uniform int uLevels;
out vec4 fragColor;
void main() {
    vec4 q = texelFetch(uQueries, ivec2(gl_FragCoord.xy), 0);
    fragColor = vec4(sampleCubeChain(q.xyz, q.w, uLevels), 1.0);
}
)";
    gpu::Program prog = test::buildFullscreenProgram("chain", kFrag);
    const gpu::VertexArray vao = gpu::VertexArray::create();
    constexpr int kW = 64, kH = 64;
    gpu::RenderTarget target(kW, kH);

    struct Case {
        int n, levels;
    };
    for (const Case c : {Case{16, 6}, Case{6, 5}, Case{4, 6}, Case{1, 3}}) {
        const CubeChain chain = patternChain(c.n, c.levels);
        // Queries: row-major, row 0 is the bottom row of the target (gl_FragCoord).
        std::mt19937 rng(std::uint32_t(c.n * 100 + c.levels));
        std::uniform_real_distribution<float> u(-1.f, 1.f);
        std::vector<glm::vec4> queries(std::size_t(kW) * kH);
        const float top = float(c.levels - 1);
        for (std::size_t k = 0; k < queries.size(); ++k) {
            glm::vec3 d(u(rng), u(rng), u(rng));
            float level = (0.5f * u(rng) + 0.5f) * top;
            switch (k % 8) {
            case 0: // a face edge: two equal largest components
                d = glm::vec3(1.f, std::copysign(1.f, d.y), 0.9f * d.z);
                break;
            case 1: // a cube corner
                d = glm::vec3(std::copysign(1.f, d.x), std::copysign(1.f, d.y),
                              std::copysign(1.f, d.z));
                break;
            case 2: // close to an edge, inside the last texel
                d = glm::vec3(d.x, 1.f, std::copysign(0.999f, d.z));
                break;
            case 3:
                level = std::round(level); // a whole level: no blend
                break;
            case 4:
                level = k % 16 == 4 ? -0.7f : top + 1.3f; // clamped
                break;
            case 5:
                if (k % 32 == 5) level = std::nanf("");
                break;
            default:
                break;
            }
            queries[k] = glm::vec4(d, level);
        }
        gpu::Texture queryTex = gpu::Texture::create(GL_TEXTURE_2D);
        glTextureStorage2D(queryTex.id(), 1, GL_RGBA32F, kW, kH);
        glTextureSubImage2D(queryTex.id(), 0, 0, 0, kW, kH, GL_RGBA, GL_FLOAT, queries.data());

        DistanceProbeLayer composite;
        composite.faces = chain.levels[0];
        const gpu::Texture layers = createCubeArray(c.n, 1);
        uploadCube(layers, 0, composite);
        const gpu::Texture levels = uploadChainArray(chain);
        gpu::UniformBuffer<glsl::DistanceParamsBlock> params;
        glsl::DistanceParamsBlock block{};
        block.params.faceRes = c.n;
        params.upload(block);

        const Image img = test::drawFullscreen(target, prog, vao, [&] {
            glBindTextureUnit(1, layers.id());
            glBindTextureUnit(3, levels.id());
            glBindTextureUnit(4, queryTex.id());
            prog.setUniform("uLayers", 1);
            prog.setUniform("uChain", 3);
            prog.setUniform("uQueries", 4);
            prog.setUniform("uLevels", c.levels);
            params.bind(glsl::kDistanceParamsBinding);
        }); // row 0 at the top
        double worst = 0.0;
        long close = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const glm::vec4 q = queries[std::size_t(y) * kW + x];
                const glm::vec3 cpu = sampleChain(chain, glm::vec3(q), q.w);
                const glm::vec3 gpu(img.rgba(x, kH - 1 - y));
                const double err = glm::length(cpu - gpu);
                worst = std::max(worst, err);
                close += err < 1e-4 ? 1 : 0;
            }
        std::printf("chain %2d^2 x %d levels (%zu GPU bytes): GLSL vs sampleChain worst %.2e, "
                    "%.2f%% within 1e-4\n",
                    c.n, c.levels, chainArrayBytes(chain), worst,
                    100.0 * double(close) / double(kW * kH));
        // A tap right on a texel boundary may round to the neighbouring texel on one side (a
        // few ulps of the face coordinate): allow a handful of the 4096 queries.
        EXPECT_GT(double(close) / double(kW * kH), 0.998) << c.n;
    }
}
