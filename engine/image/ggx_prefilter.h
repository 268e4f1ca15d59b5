#pragma once
// The GGX prefiltered radiance chain of one cube layer (Karis 2013, "Real Shading in Unreal
// Engine 4", split-sum prefilter), with a min/max distance chain for ray searches on coarse
// levels. Generic: six faces in, a chain out; nothing here knows about probes.
//
// A cube layer is six N x N RGBA float faces in the OpenGL order and orientation of
// engine/math/cube_face.glsl.h: RGB = radiance, A = distance from the cube's centre, or the
// sentinel dInf (or more) where a texel sees nothing.
//
// Levels. Level i has faces of max(1, N >> i) texels and perceptual roughness
// r_i = i / (levels - 1) (GGX alpha = r_i^2, as the shading uses): linear in perceptual
// roughness, so a lookup's fractional level is r * (levels - 1). Filament's lookup uses
// lod = maxLod * r * (2 - r), which spends more levels on low roughness; the linear map is
// the simpler one to invert and to test, and with 6 levels the first glossy level (r = 0.2,
// alpha = 0.04) still has a lobe about two texels wide at N / 2. Level 0 is the input itself,
// bit for bit (roughness 0).
//
// Filter (levels >= 1): for each texel direction R, with the N = V = R assumption,
//     L_i(R) = sum_k L(l_k) (n.l_k) / sum_k (n.l_k),  l_k = reflect(-V, h_k), h_k ~ D(h)(n.h)
// which converges to  int L(l) D(h) (n.l) dl / int D(h) (n.l) dl  over n.l > 0. N = V = R
// makes the lobe rotationally symmetric about R, so one chain serves every view; it loses
// the lobe's stretch at grazing view angles (the true lobe grows long and leans away from
// the mirror direction), so grazing glossy reflections come out too sharp and too round.
// The samples are a Hammersley set (deterministic: the same chain every run), and each one
// reads a box-filtered mip of the input at the level whose texel solid angle matches the
// sample's share of the lobe (filtered importance sampling, Krivanek & Colbert 2008), so a
// few dozen samples give a smooth result instead of noise; the price is a slight extra
// blur, measured against brute-force integration in tests/image/ggx_prefilter_test.cpp.
// Everything that gathers texels weights them by their exact solid angle, and every fetch
// reads across face edges by direction (never clamps to a face's edge), so the chain has no
// seams. The filter's inner loop is engine/image/ggx_lobe_filter.h.
//
// Distances. Distance is never blended with radiance weights: a mean of a hit and dInf is
// meaningless. Each level stores, per texel, the min and max of the finite (< dInf)
// level-0 distances whose texels overlap the texel's footprint on the same face (for
// N a power of two, the 2^i x 2^i block under it); dInf for both where there is none. The
// level's A channel holds the min as well. A footprint that mixes hits and misses reports
// its hits only. Level 0 keeps the input's A unchanged; its minMaxDistance is (A, A), or
// (dInf, dInf) for a miss.
#include "engine/image/image.h"

#include <array>
#include <limits>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace specula {

using CubeFaces = std::array<Image, 6>; // OpenGL order +X -X +Y -Y +Z -Z

struct GgxPrefilterOptions {
    int levels = 6; // level 0 (the input) included; >= 1
    // GGX samples per texel: `samples` at level 1, doubled at each further level (whose faces
    // have a quarter of the texels, so a level costs half the one before), up to maxSamples.
    int samples = 64;
    int maxSamples = 1024;
    // Added to the filtered-importance-sampling mip level: higher blurs more and aliases
    // less (Krivanek & Colbert add 1). Against brute force (64 samples, N = 128, see the
    // test), 1 gives 2-3x the mean error of 0 on a smooth sky and is also the worst of the
    // three at a small hard-edged bright disc; 0.5 has the lowest max error at the disc
    // (level 1: 0.064 against 0.070 for 0 and 0.082 for 1), and means within 1.5x of 0.
    float lodBias = 0.5f;
    // A texel whose A is >= dInf (or NaN) sees nothing; written where a footprint has no hit.
    float dInf = std::numeric_limits<float>::infinity();
};

struct CubeChain {
    std::vector<CubeFaces> levels;         // RGBA: RGB prefiltered radiance, A = min distance
    std::vector<float> roughness;          // perceptual roughness per level
    std::vector<CubeFaces> minMaxDistance; // 2 channels per level: min, max finite distance
    float dInf = std::numeric_limits<float>::infinity();
};

// r_i = i / (levels - 1); 0 when levels == 1.
float ggxChainRoughness(int level, int levels);
// The fractional level for a perceptual roughness: r * (levels - 1), clamped to the chain.
float ggxChainLevel(float roughness, int levels);

// The GGX samples per texel of a level (0 for level 0, which is copied).
int ggxChainSamples(int level, const GgxPrefilterOptions& options);

// Throws Error when the faces are not six equal square 4-channel images or an option is out
// of range. Parallel over faces x rows (oneTBB).
CubeChain prefilterGgx(const CubeFaces& faces, const GgxPrefilterOptions& options = {});

// Prefiltered radiance along dir (need not be normalised) at a fractional level (clamped to
// the chain): trilinear, bilinear within a face and across face edges, seam-free. Runs the
// shared GLSL/C++ sampler engine/math/cube_chain_sample.glsl.h, which shaders include to
// sample the same chain the same way.
glm::vec3 sampleChain(const CubeChain& chain, glm::vec3 dir, float level);

// (min, max) distance of the level's texel along dir: a nearest fetch, never blended.
glm::vec2 fetchMinMaxDistance(const CubeChain& chain, glm::vec3 dir, int level);

// Building blocks, exposed for tests and for other cube filters.
//
// Bilinear sample of a cube at direction dir with texel centres at (i + 0.5) / n. Taps past
// a face's edge read the neighbouring face's texel through that direction; at a cube
// corner, where three faces meet and a fourth tap has no texel, it reads the mean of the
// three corner texels (as seamless cube-map hardware does), so the result is continuous
// over the whole sphere.
glm::vec4 sampleCubeBilinear(const CubeFaces& faces, glm::vec3 dir);
// Exact solid angle of texel (x, y) of an n x n cube face (the same on every face). Not
// named cubeTexelSolidAngle: the distance probe asset (components/) has one taking
// (x, y, n), the same types, so the two would clash at link time.
double cubeFaceTexelSolidAngle(int n, int x, int y);

} // namespace specula
