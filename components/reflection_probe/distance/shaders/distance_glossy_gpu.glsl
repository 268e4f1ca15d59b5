// The GPU side of a distance probe's glossy chain (HAS_GLOSSY): the texel fetches
// engine/math/cube_chain_sample.glsl.h expects, reading the composite's prefiltered chain
// exactly as the CPU twin reads its images (texelFetch, no hardware filtering), so the two
// sample the same values. Included after distance_probe_gpu.glsl (uLayers, uDistance).
//
// Level 0 is the composite itself: array layers 0..5 of uLayers. Levels 1.. live in uChain,
// a mipmapped 2D array (uploadChainArray in distance_textures.h): level i at mip i - 1,
// array layers 0..5, since each level's faces are half the size of the one before. A chain
// longer than the mip pyramid (faces already 1 x 1) keeps its further 1 x 1 levels in the
// last mip, six array layers each: level i at mip min(i - 1, mips - 1), array layers
// 6 s .. 6 s + 5 with s = i - 1 - mip.
#ifndef SPECULA_DISTANCE_GLOSSY_GPU_GLSL
#define SPECULA_DISTANCE_GLOSSY_GPU_GLSL

uniform sampler2DArray uChain;

int chainMip(int level) {
    return min(level - 1, textureQueryLevels(uChain) - 1);
}

// Level i's faces are max(1, faceRes >> i) wide (uploadChainArray checks it). Computed, not
// queried: on llvmpipe, textureSize(uChain, lod) gave wrong sizes where the lod differed
// between pixels shaded together (the level varies per pixel), and every fetch then missed.
int chainFaceRes(int level) {
    return max(1, uDistance.params.faceRes >> level);
}

vec3 fetchChainTexel(int level, int face, ivec2 texel) {
    if (level == 0) return texelFetch(uLayers, ivec3(texel, face), 0).rgb;
    int mip = chainMip(level);
    return texelFetch(uChain, ivec3(texel, 6 * (level - 1 - mip) + face), mip).rgb;
}

#endif
