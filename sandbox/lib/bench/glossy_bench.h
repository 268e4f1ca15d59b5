#pragma once
// specula-sandbox glossy: the issue-14 bench of glossy reflections on the CPU twins. A
// distance probe (secant search) and a small light-field probe (8 x 8 cameras of 64^2) of the
// scene are baked once through the cooking API; then, for each roughness, every reflector gets
// that roughness, the environment-only GGX ground truth is traced (and its noise floor: seed 1
// against seed 2), and every reflector pixel is looked up six ways: envmap + chain, boxproj +
// chain, rectified (level by roughness), rectified (level by footprint), layered (every object
// layer searched, the nearest hit's footprint level) and the light field's glossy lookup.
// PSNR on the eroded reflector pixels goes to glossy.csv and a printed table,
// with each method's cost (glossy_timing.h): its GPU reflector pass as a ratio to the mirror
// envmap pass of the same run (methods with a shader; unless timing is off) and the texture
// memory it holds.
//
// --roughness is each reflector's roughness factor: a reflector with a roughness map
// (ReflectorMarkup::roughnessMap) reads factor x the map at each pixel's TEXCOORD_0
// (roughnessAt), in the truth and in every lookup, its GGX albedo included.
#include "assetcooker/lib/scene/added_reflector.h"
#include "assetcooker/lib/scene/scene_markup.h"

#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

namespace specula::cli {
class ToolCli;
}

namespace specula::sandbox {

struct GlossyBenchOptions {
    std::string scene, sky, out;
    std::vector<float> roughness{0.f, 0.05f, 0.1f, 0.2f, 0.35f, 0.5f};
    int width = 320, height = 240;
    int faceRes = 128;
    int samples = 256; // GGX truth samples per pixel
    std::vector<AddedReflector> addedReflectors;
    bool progress = true;
    bool timing = true;    // the GPU reflector pass of each method, against the mirror envmap
    int timingRounds = 15; // interleaved rounds; the median of as many frames per method
};

struct GlossyBenchRow {
    float roughness = 0.f;
    std::string method;
    double psnr = 0.0;           // NaN ("none") when no reflector pixel is in view
    double noiseFloorPsnr = 0.0; // +inf at roughness 0 (the truth is exact there)
    double ratioToEnvmap = -1.0; // pass time / the mirror envmap's; < 0: not timed
    double memoryMiB = 0.0;      // texture memory the method holds (GlossyTextures)
};

// Per roughness where a reflector has a map: the footprint row's PSNR, and the same had every
// mapped reflector taken factor x its map's mean roughness, uniformly (what one roughness
// per reflector gives), against the same per-texel truth.
struct GlossyMapVsMean {
    float roughness = 0.f;
    double mapPsnr = 0.0, meanPsnr = 0.0;
};

struct GlossyBenchResult {
    std::vector<GlossyBenchRow> rows;
    std::vector<GlossyMapVsMean> mapVsMean; // empty when no reflector has a map
    long mirrorPixels = 0;                  // reflector pixels evaluated per roughness
    double bakeSeconds = 0.0;
    double envmapMs = 0.0; // the mirror envmap pass the ratios divide by (0: not timed)
    std::string timer;     // what clock timed the passes
    std::size_t storeBytes = 0, expectedStoreBytes = 0; // see GlossyTiming
};

// The method names, in the order of the rows of each roughness.
const std::vector<std::string>& glossyBenchMethods();

// "0,0.2,0.5": each value in [0, 1]; else UsageError naming --roughness.
std::vector<float> parseRoughnessList(const std::string& text);

GlossyBenchResult runGlossyBench(const GlossyBenchOptions& options, std::ostream& log);

void addGlossyCommand(cli::ToolCli& tool);

} // namespace specula::sandbox
