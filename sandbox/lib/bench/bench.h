#pragma once
// specula-sandbox bench: every method and its accuracy sweep on several scenes, measured in
// one run against the Embree ground truth. Writes bench.csv, bench.md, accuracy_vs_time.png
// and strip_<scene>.png into the output folder.
#include "assetcooker/lib/flavours/pem/pem_samples.h"
#include "assetcooker/lib/scene/added_reflector.h"

#include <limits>
#include <ostream>
#include <string>
#include <vector>

namespace specula {

struct BenchOptions {
    std::vector<std::string> scenes; // empty: the default room and the truck room
    std::string sky;                 // empty: the default panorama
    bool quick = false;
    int width = 0, height = 0; // 0: 1024x768, quick 160x120
    int faceRes = 0;           // 0: 256, quick 64
    int maxFrames = 0;         // timed frames per row at most; 0: 64, quick 12
    std::string outDir = "bench-out";
    bool progress = true;
    // Test mirrors added to every benched scene (--add-reflector).
    std::vector<AddedReflector> addedReflectors;
    // The PEM bakes' rays per pixel side and rendering-matrix rows (PemCookSettings
    // supersample, rows, nonNegative, roundingReach): --pem-supersample, --pem-rows,
    // --pem-non-negative, --pem-rounding-reach.
    int pemSupersample = 1;
    std::string pemRows = "subray";
    bool pemNonNegative = true;
    float pemRoundingReach = PemCookSettings{}.roundingReach;
    // The PEM sample counts to bake (--pem-samples); empty: N in {4, 8, 16, 32} on the room and
    // the bowl, N = 8 elsewhere and in quick runs.
    std::vector<int> pemSamples;
    // The PEM viewpoint's path (--pem-path): "auto" the scene camera's animation where the
    // scene has one that moves (sceneCameraMoves), else the walk's orbit; "orbit"; "camera".
    std::string pemPath = "auto";
};

struct BenchRow {
    std::string scene, method, params;
    double msMedian = 0, ratioToEnvmap = 0;
    // The whole frame (scene and reflectors; FrameRenderer::frameMs) and its ratio to the
    // envmap row's frame of the same scene: what the pass ratio means for a player. NaN for
    // the ground truth (no frame).
    double frameMsMedian = std::numeric_limits<double>::quiet_NaN();
    double frameRatioToEnvmap = std::numeric_limits<double>::quiet_NaN();
    double psnr = 0, rmse = 0;         // vs environment-only ground truth
    double psnrFull = 0, rmseFull = 0; // vs the full (multi-bounce) ground truth
    double fetchesPerPixel = 0;
    std::size_t gpuBytes = 0;
    double bakeSeconds = 0;
    int frames = 0; // timed samples behind the median
};

struct BenchReport {
    std::vector<BenchRow> rows;
    std::string machine, renderer, glVersion;
    std::string timer; // how pass times were taken (FrameRenderer::timerSource)
    int width = 0, height = 0, faceRes = 0;
};

// `second scene` of the default set.
std::string truckRoomPath();
// A concave mirror bowl and a small mirror sphere in the default room: mirrors that see
// themselves and each other over much of their area (scripts/make_bowl_room.py).
std::string bowlRoomPath();
std::string skyOnlyPath(); // a mirror under the sky alone: the plan must be the plain envmap

// Runs the whole bench and writes its files; progress lines go to `log`. Throws Error
// naming the file on bad input.
BenchReport runBench(const BenchOptions& options, std::ostream& log);

} // namespace specula
