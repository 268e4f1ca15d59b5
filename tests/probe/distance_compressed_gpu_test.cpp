// A compressed probe on the GPU (issue 36, item 3): the room's probe with its composite in
// BC6H plus half distances, drawn through the COMPRESSED_COMPOSITE permutation (radiance
// sampled from the BC6H array, distances from their own), agrees with its CPU twin (which reads
// the decoded values) as the float probe does, and stays close to the float probe's frame.
#include "components/reflection_probe/distance/distance_compression.h"
#include "components/reflection_probe/distance/distance_glossy_chain.h"
#include "components/reflection_probe/distance/distance_gpu_probe.h"
#include "components/reflection_probe/distance/distance_textures.h"
#include "components/reflection_probe/distance/writer/distance_probe_writer.h"
#include "probe_fixture.h"
#include "twin_agreement.h"

#include <cstdio>

using namespace specula;
using specula::test::RoomProbe;

namespace {

class CompressedRoomProbe : public RoomProbe {
protected:
    static void SetUpTestSuite() {
        RoomProbe::SetUpTestSuite();
        DistanceProbeAsset a = readDistanceProbe(manifest());
        compressComposite(a);
        compressedDir_ = dir_ + "-bc6h";
        writeDistanceProbe(a, compressedDir_, "room.gltf");
        // The same with the GGX chain the bake cooks for rough reflectors, compressed with it.
        DistanceProbeAsset g = readDistanceProbe(manifest());
        const CubeChain chain = glossyChainOf(g);
        g.glossyLevels.assign(chain.levels.begin() + 1, chain.levels.end());
        compressComposite(g);
        writeDistanceProbe(g, glossyDir(), "room.gltf");
    }
    static void TearDownTestSuite() {
        std::filesystem::remove_all(compressedDir_);
        std::filesystem::remove_all(glossyDir());
        RoomProbe::TearDownTestSuite();
    }
    static std::string compressedManifest() { return compressedDir_ + "/manifest.json"; }
    static std::string glossyDir() { return compressedDir_ + "-glossy"; }
    static void setRoughness(float r) {
        scene_->registry().view<Reflector>().each(
            [&](ecs::Entity, Reflector& c) { c.roughness = r; });
    }
    void TearDown() override { setRoughness(0.f); }
    static std::string compressedDir_;
};

std::string CompressedRoomProbe::compressedDir_;

} // namespace

TEST_F(CompressedRoomProbe, ShaderMatchesItsTwinOnTheDecodedValues) {
    const CameraView cam = scene_->camera(kWidth, kHeight);
    const Image mask = erodedMask(scene_->groundTruth(cam, true).mirrorMask);
    for (DistanceMethod m : {DistanceMethod::Envmap, DistanceMethod::Bisection,
                             DistanceMethod::Secant, DistanceMethod::Layered}) {
        useProbe(probeFor(m), compressedManifest());
        const test::TwinAgreement t = test::compareWithTwin(*renderer_, *scene_, cam, mask);
        ASSERT_GT(t.layerPx, 500) << "the camera must see the reflectors";
        std::printf("%-9s bc6h twin vs GLSL: %ld layer px, %.3f%% within 2e-3, mean %.2e, "
                    "worst %.4f\n",
                    toString(m), t.layerPx, 100.0 * t.share(), t.mean(), t.worst);
        // The float probe's bounds (distance_gpu_test.cpp): the GPU decodes BC6H bit-exactly
        // as the twin's decoder does (bc6h_gl_test.cpp), so compression adds nothing here.
        EXPECT_GT(t.share(), 0.995) << toString(m);
        EXPECT_LT(t.mean(), 5e-4) << toString(m);
    }
}

TEST_F(CompressedRoomProbe, TheFrameStaysCloseToTheFloatProbesAndTheCompositeTakesLess) {
    const CameraView cam = scene_->camera(kWidth, kHeight);
    const Image mask = erodedMask(scene_->groundTruth(cam, true).mirrorMask);
    useProbe(probeFor(DistanceMethod::Secant));
    const Image floatFrame = renderer_->render(cam);
    useProbe(probeFor(DistanceMethod::Secant), compressedManifest());
    const Image bc6hFrame = renderer_->render(cam);
    const double psnr = compareImages(bc6hFrame, floatFrame, &mask).psnr;
    std::printf("secant: BC6H composite against float, %.2f dB over the mirror pixels\n", psnr);
    // Compression error alone (CHANGELOG.md "Storage formats": <= 0.042 dB against the ground
    // truth on four scenes); the two frames differ by the codec's error, far below the
    // method's own (~30 dB against the truth).
    EXPECT_GT(psnr, 40.0);
    const DistanceProbeAsset a = readDistanceProbe(compressedManifest());
    EXPECT_EQ(compositeBytes(a), cubeBytesBc6hR16f(a.faceRes));
    EXPECT_LT(compositeBytes(a), cubeBytesRgba32f(a.faceRes) / 3);
}

// The glossy chain of a compressed probe goes up as its BC6H blocks: the HAS_GLOSSY shader
// samples them, the twin reads their decoding (the asset's glossyLevels), and the two agree as
// the float chain's do (distance_glossy_gpu_test.cpp); the GPU holds the blocks' bytes.
TEST_F(CompressedRoomProbe, TheGlossyChainIsSampledFromItsBlocks) {
    constexpr float kRoughness = 0.2f;
    const CameraView cam = scene_->camera(kWidth, kHeight);
    const Image mask = erodedMask(scene_->groundTruth(cam, true).mirrorMask);
    useProbe(probeFor(DistanceMethod::Secant), glossyDir() + "/manifest.json");
    setRoughness(0.f);
    renderer_->render(cam);
    const std::size_t mirrorBytes = renderer_->probes().stats().probeGpuBytes;
    setRoughness(kRoughness);
    const Image colour = renderer_->render(cam);
    const Image pos = renderer_->render(cam, 1);
    const Image dir = renderer_->render(cam, 2);
    const Image nv = renderer_->render(cam, 3);
    const Image lighting = test::withoutGgxAlbedo(colour, nv, mask, kRoughness);
    const ecs::Entity probe = scene_->probeEntity();
    const DistanceStore& store = *renderer_->probes().store<DistanceStore>();
    const std::shared_ptr<const CubeChain> chain = store.glossyChain(probe);
    ASSERT_TRUE(chain);
    const DistanceProbeAsset& asset = *store.asset(probe);
    ASSERT_EQ(asset.glossyBlocks.size() + 1, chain->levels.size());
    const CpuDistanceProbe twin(asset, *store.config(probe), chain);
    const test::PixelAgreement a = test::agreeByPixel(
        lighting, pos, dir, mask,
        [&](glm::vec3 x, glm::vec3 l) { return twin.glossyRadiance(x, l, kRoughness); }, 2e-3);
    std::printf("secant glossy r %.1f, BC6H chain, twin vs GLSL: %ld px, %.3f%% within 2e-3, "
                "mean %.2e, worst %.2e; chain %zu bytes BC6H against %zu float\n",
                kRoughness, a.n, 100.0 * a.share(), a.mean(), a.worst,
                chainArrayBytes(*chain, true), chainArrayBytes(*chain));
    ASSERT_GT(a.n, 1000) << "the camera must see the reflectors";
    EXPECT_GT(a.share(), 0.99);
    EXPECT_LT(a.mean(), 5e-4);
    // The chain adds its blocks' bytes to the probe's, not a float chain's (16x more).
    EXPECT_EQ(renderer_->probes().stats().probeGpuBytes - mirrorBytes,
              chainArrayBytes(*chain, true));
    std::size_t blockBytes = 0; // what the asset stores; the array also pads its slots
    for (const std::vector<std::uint8_t>& b : asset.glossyBlocks)
        blockBytes += b.size();
    EXPECT_GE(chainArrayBytes(*chain, true), blockBytes);
    EXPECT_LT(chainArrayBytes(*chain, true), chainArrayBytes(*chain) / 8);
}
