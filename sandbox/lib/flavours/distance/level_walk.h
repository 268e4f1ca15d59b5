#pragma once
// specula-sandbox level: a reflector walked through a level's probes (issue 13). The level is
// baked (or read), the reflectors move along a path through several probes' influence
// volumes, a camera follows them, and every frame's reflector pixels are looked up three
// ways (the nearest probe alone, engine-style blending, visibility-aware blending) on the CPU
// twin of the distance lookup and compared with Embree's environment-only truth. Writes
// frames.csv (per frame: position, PSNR per blend, the probes and weights at the reflector,
// how often a probe was hidden), summary.csv (mean and worst PSNR, on all frames and on the
// frames where probes overlap; the pop metric) and level_walk.png (truth and the three
// blends where engine-style blending is worst, error maps below). With timing, the level is
// also drawn on the GPU (DistanceLevelStore) for every blend and K
// = 1, 2, 4 at the frame where probes overlap with the most reflector pixels, and its
// reflector pass timed against one probe's envmap (timing.csv).
#include "assetcooker/lib/scene/added_reflector.h"
#include "assetcooker/lib/scene/reflector_roughness_maps.h"

#include <glm/vec3.hpp>

#include <array>
#include <ostream>
#include <string>
#include <vector>

namespace specula::sandbox {

struct LevelWalkOptions {
    std::string scene, sky, out;
    std::string level;             // a baked level folder; empty: bake one into out/level
    bool allowStale = false;       // walk a --level baked from another scene (a warning each)
    bool skyFromLevel = false;     // a --level's own sky, not `sky`, lights the truth
    std::vector<glm::vec3> path;   // world points; empty: through every probe in order
    std::vector<glm::vec3> probes; // baking: probe positions (--probe), else the markup's
    std::string probeList;         // baking: --probes FILE.json (level_bake.h)
    std::vector<AddedReflector> addedReflectors; // dropped into the scene before anything
    int frames = 40;
    int width = 320, height = 240;
    int faceRes = 128;             // when baking
    int k = 4;                     // probes blended per pixel at most
    std::string method = "secant"; // each probe's lookup
    float tolerance = 0.01f;       // d_e
    bool progress = true;
    bool timing = true; // the GPU reflector pass per blend and K, against envmap
    // Every reflector's perceptual roughness (issue 14): its factor, times its roughness map
    // per pixel where it has one (ReflectorRoughnessMaps, in the truth and the twin); > 0: the
    // truth is Embree's GGX reflection (glossySamples a pixel) and the level reads every
    // probe's chain.
    float roughness = 0.f;
    int glossySamples = 256;
};

struct LevelWalkBlendSummary {
    std::string blend;
    // Over the frames with a PSNR (meanPsnr, worstPsnr in compare.h); NaN when none has one.
    double meanPsnr = 0, worstPsnr = 0;           // every frame
    double overlapMeanPsnr = 0, overlapWorst = 0; // frames where 2+ probes have influence
    double pop = 0;       // largest frame-to-frame RMS change of the reflector pixels
    double truthPop = 0;  // the truth's own change over those two frames
    double popExcess = 0; // largest (change - truth's change) over all frame pairs
};

// The level shader's reflector pass at one frame of the walk, against one probe's envmap
// pass drawn the same way (ratios only on a software rasteriser: FrameRenderer::passMs).
struct LevelPassTime {
    std::string blend;
    int k = 0;
    double ms = 0, ratioToEnvmap = 0;
    int frames = 0; // timed frames the median rests on
};

struct LevelWalkResult {
    std::vector<LevelWalkBlendSummary> blends; // nearest, engine, visibility
    int overlapFrames = 0;
    // Mean texture fetches per reflector pixel, [nearest, engine, visibility][K = 1, 2, 4]
    // (the CPU twin's count; an envmap lookup is 1).
    std::array<std::array<double, 3>, 3> fetchesPerPixel{};
    double hiddenShare = 0;   // visibility: probe lookups whose probe did not see the hit
    double fallbackShare = 0; // pixels that no probe with influence sees (engine blend used)
    double outsideShare = 0;  // pixels outside every influence volume (nearest probe)
    double bakeSeconds = 0;   // 0 when the level was read
    std::vector<LevelPassTime> passTimes; // empty without --timing
    int timedFrame = -1;                  // the walk frame they were taken at
    std::string timer;                    // what clock measured them
    // The visibility blend with the mirror lookup against the same truth (at roughness > 0:
    // what a rough reflector drew before the level read chains).
    double mirrorLookupMeanPsnr = 0, mirrorLookupWorstPsnr = 0;
    // The level store's textures: composites and sky, and the chains a rough reflector adds.
    std::size_t mirrorBytes = 0, chainBytes = 0;
};

LevelWalkResult runLevelWalk(const LevelWalkOptions& options, std::ostream& log);

} // namespace specula::sandbox

namespace specula::cli {
class ToolCli;
}

namespace specula::sandbox {

// Registers `specula-sandbox level` (level_walk_cli.cpp).
void addLevelCommand(cli::ToolCli& tool);

} // namespace specula::sandbox
