// The host API's unmanaged mode: the host asks DistanceHostProbe::describe what a probe reads,
// creates those textures and the parameter buffer itself and hands them over. Held to the
// managed mode, which the host tests hold to the CPU twins: the same host shader drawn through
// either probe gives the same image bit for bit (distance: plain and BC6H-compressed assets,
// with the glossy chain; a glossy light field; PEM of box and distance geometry), the managed
// distance probe's own textures match the description, and the host's objects outlive the
// probe. A texture or buffer that does not fit is an error value naming the
// asset and the texture, and no host texture is written.
#include "assetcooker/lib/bake/cook.h"
#include "assetcooker/lib/level/level_bake.h"
#include "components/reflection_probe/distance/distance_host_probe.h"
#include "components/reflection_probe/distance/distance_level_host_probe.h"
#include "components/reflection_probe/lightfield/lightfield_host_probe.h"
#include "components/reflection_probe/pem/pem_host_probe.h"
#include "components/reflection_probe/pem/writer/pem_probe_writer.h"
#include "engine/context/context.h"
#include "engine/gpu/render_target.h"
#include "engine/image_io/compare.h"
#include "pem/pem_random_asset.h"
#include "support/fullscreen_pass.h"
#include "support/host_sphere.h"
#include "support/probe_room.h"
#include "support/scratch_dir_test.h"
#include "two_room_level_gpu_fixture.h" // kTwoRoomsScene

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>

namespace specula {
namespace {

constexpr int kW = 96, kH = 72;

// The host's main after Specula's library and the sphere ray cast (a sphere of radius 0.3 at
// the probe centre): mirror on the left half, rough (0.35) on the right.
const char* kHostMain = R"(
void main() {
    vec3 p, d;
    vec2 ndc;
    if (!sphereHit(p, d, ndc)) { colour = vec4(0.0); return; }
    colour = vec4(speculaReflect(p, p - uSphere.xyz, d, ndc.x < 0.0 ? 0.0 : 0.35), 1.0);
}
)";

// The host's side of the unmanaged mode: one texture per spec, one buffer, made as any engine
// makes its own and deleted by the host only.
struct HostObjects {
    std::vector<gpu::HostTexture> textures;
    GLuint buffer = 0;
    HostObjects(const HostLayout& layout, GLenum swapFormatOf = 0) {
        for (const gpu::TextureSpec& spec : layout.textures) {
            GLuint id = 0;
            glCreateTextures(spec.target, 1, &id);
            const GLenum format =
                spec.name == "uLayers" && swapFormatOf ? swapFormatOf : spec.internalFormat;
            if (spec.target == GL_TEXTURE_2D)
                glTextureStorage2D(id, spec.levels, format, spec.width, spec.height);
            else
                glTextureStorage3D(id, spec.levels, format, spec.width, spec.height, spec.layers);
            textures.push_back({spec.name, id});
        }
        if (layout.paramsBytes == 0) return; // a light field has no uniform buffer
        glCreateBuffers(1, &buffer);
        glNamedBufferStorage(buffer, GLsizeiptr(layout.paramsBytes), nullptr,
                             GL_DYNAMIC_STORAGE_BIT);
    }
    ~HostObjects() {
        for (const gpu::HostTexture& t : textures)
            glDeleteTextures(1, &t.id);
        if (buffer) glDeleteBuffers(1, &buffer);
    }
    bool allAlive() const {
        return (buffer == 0 || glIsBuffer(buffer)) &&
               std::all_of(textures.begin(), textures.end(),
                           [](const auto& t) { return glIsTexture(t.id); });
    }
};

class HostUnmanaged : public test::ScratchDirTest,
                      public ::testing::WithParamInterface<DistanceCompression> {
protected:
    HostUnmanaged() : ScratchDirTest("specula-host-unmanaged") {}
    static void SetUpTestSuite() { context_ = gpu::GlContext::createHeadless().release(); }
    static void TearDownTestSuite() {
        delete context_;
        context_ = nullptr;
    }

    std::string cook(DistanceCompression compression) {
        test::ProbeRoom room;
        DistanceCookSettings s;
        s.faceRes = 64;
        s.planned = s.recordPlan = false;
        s.compression = compression;
        CookOptions o;
        o.out = (root_ / "probe").string();
        o.flavour = s;
        o.progress = false;
        cookProbe(room.probeScene(), o, nullptr);
        return (root_ / "probe" / "manifest.json").string();
    }

    // The host's frame: a sphere of `radius` at `c` (mirror left, rough right) through `probe`.
    template <typename Probe> static Image draw(const Probe& probe, glm::vec3 c, float radius) {
        const glm::vec3 eye = c + glm::vec3(0.f, 0.4f, 1.4f);
        const test::HostSphereView view{
            glm::inverse(glm::perspective(glm::radians(40.f), float(kW) / float(kH), 0.05f, 100.f) *
                         glm::lookAt(eye, c, glm::vec3(0.f, 1.f, 0.f))),
            eye, glm::vec4(c, radius), kW, kH};
        gpu::Program prog = test::buildFullscreenProgram(
            "host_unmanaged", probe.glslLibrary() + test::kHostSphereGlsl + kHostMain);
        gpu::RenderTarget target(kW, kH);
        const gpu::VertexArray vao = gpu::VertexArray::create();
        return test::drawFullscreen(target, prog, vao, [&] {
            view.setUniforms(prog);
            probe.bindTo(prog.id());
        });
    }
    static Image draw(const DistanceHostProbe& probe) { return draw(probe, probe.centre(), 0.3f); }

    // The managed and the unmanaged probe of one asset draw the same frame, bit for bit, and the
    // host's objects outlive the unmanaged one.
    template <typename Probe, typename Options>
    void expectSameFrame(const std::string& manifest, Options options, const HostLayout& layout,
                         const char* what, glm::vec3 c, float radius) {
        ASSERT_TRUE(layout) << layout.error;
        const HostResult<Probe> managed = Probe::create(manifest, options);
        ASSERT_TRUE(managed) << managed.error;
        const Image expected = draw(*managed.probe, c, radius);
        HostObjects host(layout);
        options.unmanaged.textures = host.textures;
        options.unmanaged.paramsBuffer = host.buffer;
        {
            const HostResult<Probe> unmanaged = Probe::create(manifest, options);
            ASSERT_TRUE(unmanaged) << unmanaged.error;
            const Image image = draw(*unmanaged.probe, c, radius);
            const ImageStats stats = compareImages(image, expected);
            int lit = 0;
            for (float v : image.pixels)
                lit += v > 0.f;
            std::printf("[host-unmanaged] %s: %zu host textures, %d lit channels, max diff %.6f\n",
                        what, host.textures.size(), lit, stats.maxError);
            EXPECT_GT(lit, kW * kH / 4) << what << ": the sphere must fill part of the frame";
            EXPECT_EQ(stats.maxError, 0.f) << what << ": the same data and shader, bit for bit";
        }
        EXPECT_TRUE(host.allAlive()) << what << ": the probe never deletes the host's objects";
        EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR)) << what;
    }

    static inline gpu::GlContext* context_ = nullptr;
};

TEST_P(HostUnmanaged, DrawsWhatTheManagedProbeDraws) {
    const std::string manifest = cook(GetParam());
    DistanceHostOptions options;
    options.glossy = true;
    const HostLayout layout = DistanceHostProbe::describe(manifest, options);
    ASSERT_TRUE(layout) << layout.error;
    std::vector<std::string> names;
    for (const gpu::TextureSpec& t : layout.textures)
        names.push_back(t.name);
    const bool compressed = GetParam() == DistanceCompression::Bc6h;
    // The room's cooked object layers: the planned lookup is layered and reads their tiles.
    std::vector<std::string> expected = {"uSky",       "uLayers", "uTileAtlas",
                                         "uTileTable", "uChain",  "uGgxAlbedo"};
    if (compressed) expected.insert(expected.begin() + 2, "uLayerDistance");
    EXPECT_EQ(names, expected);
    EXPECT_EQ(layout.textures[1].internalFormat,
              GLenum(compressed ? GL_COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT : GL_RGBA32F));

    const DistanceHostResult managed = DistanceHostProbe::create(manifest, options);
    ASSERT_TRUE(managed) << managed.error;
    const DistanceGpuProbe& g = managed.probe->gpu();
    // The description is what the managed probe allocates.
    const std::pair<const char*, GLuint> owned[] = {{"uSky", g.sky.id()},
                                                    {"uLayers", g.layers.id()},
                                                    {"uLayerDistance", g.layerDistance.id()},
                                                    {"uTileAtlas", g.tiles.atlas.id()},
                                                    {"uTileTable", g.tiles.table.id()},
                                                    {"uChain", g.glossyTexture.id()}};
    for (const auto& [name, id] : owned) {
        const auto spec = std::find_if(layout.textures.begin(), layout.textures.end(),
                                       [&](const auto& t) { return t.name == name; });
        if (spec == layout.textures.end()) {
            EXPECT_EQ(id, 0u) << name << " is allocated but not described";
            continue;
        }
        EXPECT_EQ(gpu::textureMismatch(id, *spec), "") << name;
    }
    const Image expectedImage = draw(*managed.probe);

    HostObjects host(layout);
    options.unmanaged.textures = host.textures;
    options.unmanaged.paramsBuffer = host.buffer;
    {
        const DistanceHostResult unmanaged = DistanceHostProbe::create(manifest, options);
        ASSERT_TRUE(unmanaged) << unmanaged.error;
        EXPECT_EQ(unmanaged.probe->gpu().layers.id(), host.textures[1].id);
        EXPECT_FALSE(unmanaged.probe->gpu().layers.owned());
        const Image image = draw(*unmanaged.probe);
        const ImageStats stats = compareImages(image, expectedImage);
        int lit = 0;
        for (float v : image.pixels)
            lit += v > 0.f;
        std::printf("[host-unmanaged] %s: %zu host textures, %d lit channels, max diff %.6f\n",
                    compressed ? "bc6h" : "float", host.textures.size(), lit, stats.maxError);
        EXPECT_GT(lit, kW * kH / 2) << "the sphere must fill part of the frame";
        EXPECT_EQ(stats.maxError, 0.f) << "the same data and shader, bit for bit";
    }
    EXPECT_TRUE(host.allAlive()) << "the probe never deletes the host's objects";
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

INSTANTIATE_TEST_SUITE_P(Formats, HostUnmanaged,
                         ::testing::Values(DistanceCompression::None, DistanceCompression::Bc6h),
                         [](const auto& info) {
                             return info.param == DistanceCompression::Bc6h ? "Bc6h" : "Float";
                         });

using HostUnmanagedFlavours = HostUnmanaged;

TEST_F(HostUnmanagedFlavours, LightFieldAndPemDrawWhatTheirManagedProbesDraw) {
    test::ProbeRoom room;
    LightFieldCookSettings lf;
    lf.cameras = 8;
    lf.imageRes = 32;
    CookOptions o;
    o.out = (root_ / "lightfield").string();
    o.flavour = lf;
    o.progress = false;
    cookProbe(room.probeScene(), o, nullptr);
    const std::string lightField = (root_ / "lightfield" / "manifest.json").string();
    const LightFieldHostOptions glossy{.glossy = true};
    const HostLayout lfLayout = LightFieldHostProbe::describe(lightField, glossy);
    ASSERT_TRUE(lfLayout) << lfLayout.error;
    ASSERT_EQ(lfLayout.textures.size(), 2u); // the atlas with its mips, the GGX albedo
    EXPECT_GT(lfLayout.textures[0].levels, 1);
    const LightFieldAsset lfAsset = readLightFieldProbe(lightField);
    expectSameFrame<LightFieldHostProbe>(lightField, glossy, lfLayout, "lightfield",
                                         lfAsset.cellCentre, 0.5f * lfAsset.halfCell());

    for (const bool distance : {false, true}) {
        PemAsset a =
            test::randomAsset(16, 3, glm::vec3(-2.f, -1.f, -3.f), glm::vec3(2.f, 3.f, 2.f));
        if (distance) test::addDistanceGeometry(a, 16);
        const std::string dir = (root_ / (distance ? "pem_distance" : "pem_box")).string();
        writePemProbe(a, dir, "");
        const std::string pem = dir + "/manifest.json";
        const HostLayout layout = PemHostProbe::describe(pem);
        ASSERT_TRUE(layout) << layout.error;
        EXPECT_EQ(layout.textures.size(), distance ? 2u : 1u);
        EXPECT_EQ(layout.paramsBytes, sizeof(glsl::PemParams));
        expectSameFrame<PemHostProbe>(pem, PemHostOptions{.settings = {.parameter = 0.3f}}, layout,
                                      distance ? "pem distance" : "pem box", a.centre, 0.3f);
    }
}

TEST_F(HostUnmanagedFlavours, ALevelDrawsWhatItsManagedLevelDraws) {
    test::ProbeRoom room(test::kTwoRoomsScene, "");
    LevelCookOptions o;
    o.cook.scene = test::kTwoRoomsScene;
    o.cook.out = (root_ / "level").string();
    DistanceCookSettings d;
    d.faceRes = 32;
    d.planned = false;
    o.cook.flavour = d;
    o.cook.progress = false;
    const std::string index = cookLevel(room.probeScene(), o, nullptr).index;
    DistanceLevelHostOptions options;
    options.glossy = true;
    const HostLayout layout = DistanceLevelHostProbe::describe(index, options);
    ASSERT_TRUE(layout) << layout.error;
    std::vector<std::string> names;
    for (const gpu::TextureSpec& t : layout.textures)
        names.push_back(t.name);
    EXPECT_EQ(names, (std::vector<std::string>{"uLevelLayers", "uLevelChain", "uGgxAlbedo"}));
    EXPECT_EQ(layout.textures[0].layers, 12) << "two probes, six faces each";
    expectSameFrame<DistanceLevelHostProbe>(index, options, layout, "level",
                                            glm::vec3(0.2f, 1.2f, 0.f), 0.35f);
}

using HostUnmanagedRefusal = HostUnmanaged;

TEST_F(HostUnmanagedRefusal, ObjectsThatDoNotFitAreErrorValuesNamingThem) {
    const std::string manifest = cook(DistanceCompression::None);
    DistanceHostOptions options;
    options.glossy = true;
    const HostLayout layout = DistanceHostProbe::describe(manifest, options);
    ASSERT_TRUE(layout) << layout.error;
    auto refusal = [&](const DistanceHostOptions& o) {
        const DistanceHostResult made = DistanceHostProbe::create(manifest, o);
        EXPECT_FALSE(made);
        EXPECT_NE(made.error.find(manifest), std::string::npos) << made.error;
        EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR)) << made.error;
        return made.error;
    };

    {
        const HostObjects wrongFormat(layout, GL_RGBA16F);
        // The sky is allocated first; a sentinel in it shows nothing is uploaded before every
        // texture has been checked.
        const GLuint sky = wrongFormat.textures[0].id;
        const float sentinel[4] = {7.f, 7.f, 7.f, 7.f};
        glClearTexImage(sky, 0, GL_RGBA, GL_FLOAT, sentinel);
        DistanceHostOptions o = options;
        o.unmanaged.textures = wrongFormat.textures;
        const std::string error = refusal(o);
        EXPECT_NE(error.find("textures.uLayers"), std::string::npos) << error;
        EXPECT_NE(error.find("internal format is GL_RGBA16F"), std::string::npos) << error;
        std::vector<float> texels(std::size_t(layout.textures[0].width) *
                                  std::size_t(layout.textures[0].height) * 4);
        glGetTextureImage(sky, 0, GL_RGBA, GL_FLOAT, GLsizei(texels.size() * sizeof(float)),
                          texels.data());
        EXPECT_TRUE(std::all_of(texels.begin(), texels.end(), [](float v) { return v == 7.f; }))
            << "the host's sky was written before the refusal";
    }
    {
        HostObjects missing(layout);
        DistanceHostOptions o = options;
        o.unmanaged.textures = missing.textures;
        std::erase_if(o.unmanaged.textures,
                      [](const gpu::HostTexture& t) { return t.name == "uChain"; });
        const std::string error = refusal(o);
        EXPECT_NE(error.find("textures.uChain"), std::string::npos) << error;
        EXPECT_NE(error.find("no texture"), std::string::npos) << error;
    }
    {
        HostObjects host(layout);
        GLuint small = 0;
        glCreateBuffers(1, &small);
        glNamedBufferStorage(small, 16, nullptr, GL_DYNAMIC_STORAGE_BIT);
        DistanceHostOptions o = options;
        o.unmanaged.textures = host.textures;
        o.unmanaged.paramsBuffer = small;
        const std::string error = refusal(o);
        EXPECT_NE(error.find("paramsBuffer"), std::string::npos) << error;
        EXPECT_NE(error.find("holds 16 bytes"), std::string::npos) << error;
        glDeleteBuffers(1, &small);
    }
}

} // namespace
} // namespace specula
