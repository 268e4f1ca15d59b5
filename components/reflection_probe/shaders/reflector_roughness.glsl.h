// A rough reflector's perceptual GGX roughness at this pixel (alpha = roughness^2): its
// factor times its roughness map (the glTF metallic-roughness texture's G channel) at the
// mesh's TEXCOORD_0, clamped to [0, 1]; the factor alone when compiled without
// HAS_ROUGHNESS_MAP (a reflector of uniform roughness reads no texture). The C++ twin is
// roughnessAt (reflector_roughness.h): sampleBilinear of the float map with Wrap::Repeat,
// which is what this texture is (roughnessMapTexture in flavour_store_base.h): the map's G
// stored as R32F in the red channel, GL_LINEAR, no mipmaps, GL_REPEAT on S and T.
#ifndef SPECULA_REFLECTOR_ROUGHNESS_GLSL_H
#define SPECULA_REFLECTOR_ROUGHNESS_GLSL_H

#if HAS_ROUGHNESS_MAP
uniform sampler2D uRoughnessMap;

float reflectorRoughness(float factor, vec2 uv) {
    return clamp(factor * textureLod(uRoughnessMap, uv, 0.0).r, 0.0, 1.0);
}
#else
float reflectorRoughness(float factor, vec2 uv) { return factor; }
#endif

#endif
