// The GPU side of a level's glossy chains (HAS_GLOSSY, issue 14): the texel fetches
// engine/math/cube_chain_sample.glsl.h expects, for the probe `gProbe` names, read exactly as
// the CPU twin reads its chains (texelFetch, no hardware filtering). Included after
// distance_level_gpu.glsl (uLevelLayers, uLevel, gProbe).
//
// Level 0 is the probe's composite itself: array layers 6 gProbe .. 6 gProbe + 5 of
// uLevelLayers. Levels 1.. of every probe live in uLevelChain, the mipmapped 2D array of
// uploadChainArrays (distance_textures.h): the probes' chains one after the other, each
// uChainSlots x 6 array layers, laid out within as a single probe's chain is
// (distance_glossy_gpu.glsl): level i at mip min(i - 1, mips - 1), slot i - 1 - mip.
#ifndef SPECULA_DISTANCE_LEVEL_GLOSSY_GPU_GLSL
#define SPECULA_DISTANCE_LEVEL_GLOSSY_GPU_GLSL

uniform sampler2DArray uLevelChain;
uniform int uChainSlots; // array layers of one probe's chain, / 6

// Computed, not queried (see distance_glossy_gpu.glsl): every probe of a level has the same
// face size.
int chainFaceRes(int level) {
    return max(1, uLevel.probes[gProbe].lookup.faceRes >> level);
}

vec3 fetchChainTexel(int level, int face, ivec2 texel) {
    if (level == 0) return texelFetch(uLevelLayers, ivec3(texel, gProbe * 6 + face), 0).rgb;
    int mip = min(level - 1, textureQueryLevels(uLevelChain) - 1);
    int slot = gProbe * uChainSlots + level - 1 - mip;
    return texelFetch(uLevelChain, ivec3(texel, 6 * slot + face), mip).rgb;
}

#endif
