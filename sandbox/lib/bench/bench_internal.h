#pragma once
// What the bench's parts share (bench.cpp, bench_pem.cpp): measuring one probe row against
// the ground truth of its camera, and the row's progress line.
#include "components/reflection_probe/pem/pem_asset.h"
#include "components/reflection_probe/pem/pem_probe.h"
#include "sandbox/lib/bench/accuracy_plot.h"
#include "sandbox/lib/bench/bench.h"
#include "sandbox/lib/bench/bench_methods.h"
#include "sandbox/lib/flavours/distance/error_budget.h"
#include "sandbox/lib/render/frame_renderer.h"
#include "sandbox/lib/render/reflection_scene.h"

#include <ostream>
#include <string>
#include <vector>

namespace specula {

struct CookResult; // assetcooker/lib/bake/cook.h

// The ground truth of one camera: environment only, full (multi-bounce), and the reflector
// pixels measured (the mirror mask eroded by one pixel).
struct BenchTruth {
    GroundTruthImage env, full;
    Image mask;
};

// Timed frames per row: the median settles between minFrames and maxFrames.
struct BenchFrameBudget {
    int minFrames = 6, maxFrames = 12;
};

// Times the reflector pass of the probe just synced from `cam`, renders it and compares it
// with both truths: fills msMedian, frames, psnr/rmse (env and full) and gpuBytes. Returns
// the image.
Image measureProbeRow(FrameRenderer& fr, const CameraView& cam, const BenchTruth& truth,
                      BenchFrameBudget budget, BenchRow& row);

// Syncs the probe just set on `scene` into `fr`. A method the asset cannot serve (layers of a
// scene without objects) is logged as skipped ("  room layered d_e=0.01: skipped (...)") and
// false returned: the bench leaves the row out rather than abort.
bool syncBenchProbe(FrameRenderer& fr, ReflectionScene& scene, const BenchRow& row,
                    std::ostream& log);

// "  room envmap -: 0.123 ms (x1.00), PSNR 30.1 dB, 1.00 fetches/px"
void logBenchRow(std::ostream& log, const BenchRow& row);

// Texture fetches per reflector pixel of the synced distance probe, counted by the CPU twin
// on the shader's own inputs (probe-local position and reflected direction read back from
// the GPU); NaN when the scene's probe is not a distance probe.
double countFetches(FrameRenderer& fr, ReflectionScene& scene, const CameraView& cam,
                    const Image& mask);

// Which PEMs the bench bakes on each scene: one per sample count, each inferred for the
// bench's frame size (the pixels it is drawn at).
struct PemBenchSweep {
    std::vector<int> samples; // e.g. {4, 8, 16, 32}
    int faceRes = 128;
    int width = 0, height = 0;
    int supersample = 1;         // PemCookSettings::supersample
    std::string rows = "subray"; // PemCookSettings::rows
    bool nonNegative = false;    // PemCookSettings::nonNegative
    float roundingReach = 0.f;   // PemCookSettings::roundingReach
    // The viewpoint follows the scene camera's animation (PemCookSettings::path "camera";
    // cameraPathView) instead of the walk's orbit.
    bool cameraPath = false;
    // The single-bounce method the PEM is compared with, drawn from the PEM's own cameras
    // (the other rows see the scene camera): its manifest, settings and row label. Empty
    // asset: none.
    std::string referenceAsset;
    MethodVariant reference;
    double referenceBakeSeconds = 0;
};

// The PEM rows of one scene, appended to report.rows and the scene's plot panel: per sample
// count N, one PEM baked through the cooking API into outDir/probes/<scene>_pemN, drawn from
// the walk orbit's camera (or the camera path's) at a sample's viewpoint ("N=8 t=on", t = 0)
// and half-way between the first two samples ("t=off", pemBenchHalfWay), each against the
// ground truth of that camera. The
// cooker's own fit (on and half-way, over all samples) and inference time go to the log.
// A scene the PEM cannot be baked for is logged and left without rows.
// The PEM settings the sweep bakes N samples with, the camera of parameter t, and the
// parameter half-way between the first two samples (0.5 / N on the orbit's loop, 0.5 / (N - 1)
// on the open camera path).
PemCookSettings pemBenchSettings(const PemBenchSweep& sweep, int samples);
CameraView pemBenchCamera(const ReflectionScene& scene, const PemBenchSweep& sweep, float t);
float pemBenchHalfWay(const PemBenchSweep& sweep, int samples);

void appendPemRows(ReflectionScene& scene, FrameRenderer& fr, const std::string& sceneName,
                   const std::string& outDir, const PemBenchSweep& sweep, BenchFrameBudget budget,
                   double envmapMs, BenchReport& report, PlotPanel& panel, std::ostream& log);

// Texture fetches per reflector pixel of the blend at `probe`, counted by the CPU twin on the
// camera's reflector rays as Embree finds them (the shader's inputs up to normal
// interpolation): a distance-geometry lookup reads the distance cube while it searches; a
// trilinear read of MIP levels counts as one filtered fetch, as a bilinear one does.
double pemFetchesPerPixel(ProbeScene& scene, const CameraView& cam, const PemAsset& asset,
                          const PemProbe& probe);

// The MIP comparison of one PEM bake (issue 12: every level inferred together), N = samples
// of `level0` (an appendPemRows bake): the same settings baked again with every level down to
// 1^2 faces inferred (outDir/probes/<scene>_pemN_mip, rows "N=.. t=on mip") and level0's maps
// with their box-filtered chain (<scene>_pemN_filtered, rows "... filtered-mip"), drawn on
// and off the manifold as the level-0 rows; a log line compares the three.
void appendPemMipRows(ReflectionScene& scene, FrameRenderer& fr, const std::string& sceneName,
                      const std::string& outDir, const PemBenchSweep& sweep, int samples,
                      const CookResult& level0, BenchFrameBudget budget, double envmapMs,
                      BenchReport& report, PlotPanel& panel, std::ostream& log);

// The storage-format rows of one scene (issue 36): the probe in probeDir with its composite
// compressed (compressComposite: BC6H radiance, R16F or R32F distance) written to
// probeDir_bc6h, and every distance method at d_e = 0.01 (or its only row) drawn from it on
// the GPU against `truth`: rows "<params> bc6h" appended to report.rows, their GPU bytes and
// PSNR beside the float rows'. A probe that cannot be compressed is logged and left out.
void appendFormatRows(ReflectionScene& scene, FrameRenderer& fr, const CameraView& cam,
                      const BenchTruth& truth, BenchFrameBudget budget,
                      const std::string& sceneName, const std::string& probeDir,
                      const std::vector<MethodVariant>& variants, double envmapMs,
                      BenchReport& report, std::ostream& log);

// The budget bakes faces twice the bench's per side only up to this size: the bake grows
// with the texels (4x), and 512^2 is the largest the full bench's 256^2 doubles to.
constexpr int kBudgetMaxFaceRes = 512;

// The error budget (error_budget.h) of one scene, appended to `budgets`: per distance method
// at d_e = 0.01 (or its only row), over the reflector rays of `truth` from `cam`, on the
// probe baked in probeDir at faceRes; the faces 2x per side are baked into probeDir_2x when
// within kBudgetMaxFaceRes (else the reason is logged and kept in the budget). Each budget
// takes its GPU row's MSE from `rows`. Methods the asset cannot serve are logged and left
// out, like their rows.
void appendErrorBudgets(ReflectionScene& scene, const CameraView& cam, const BenchTruth& truth,
                        const std::string& sceneName, const std::string& probeDir, int faceRes,
                        bool progress, const std::vector<MethodVariant>& variants,
                        const std::vector<BenchRow>& rows, std::vector<MethodErrorBudget>& budgets,
                        std::ostream& log);

} // namespace specula
