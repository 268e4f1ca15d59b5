#pragma once
// Distance probes' textures, written once for the single-probe store and the level store:
// cube layers as an RGBA32F texture array (six faces per cube, A = distance) and the sky
// panorama. Need a current GL 4.5 context.
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "engine/gpu/gl_objects.h"

#include <cstddef>

namespace specula {

// An array of `cubes` x 6 faces of faceRes^2 texels, bilinear, clamped at the face edges.
gpu::Texture createCubeArray(int faceRes, int cubes);
// Writes `layer`'s six faces into array layers 6 cube .. 6 cube + 5.
void uploadCube(const gpu::Texture& array, int cube, const DistanceProbeLayer& layer);
std::size_t cubeArrayBytes(int faceRes, int cubes);

// The equirectangular sky, bilinear, repeating around the horizon.
gpu::Texture uploadSkyTexture(const Image& sky);
std::size_t skyTextureBytes(const Image& sky);

} // namespace specula
