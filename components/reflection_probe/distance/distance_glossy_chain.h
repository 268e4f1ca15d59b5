#pragma once
// The composite's GGX prefiltered chain (engine/image/ggx_prefilter.h) that glossy lookups
// read, for the GPU store and the CPU twins alike: the levels the bake cooked
// (DistanceProbeAsset::glossyLevels) when the asset has them, else the composite prefiltered
// here (prefilterGgx with `options` and the asset's d_inf), as the bake would have.
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "engine/image/ggx_prefilter.h"

namespace specula {

// Level 0 is the composite (layer 0) itself; levels 1 .. L - 1 the prefiltered ones, at
// perceptual roughness i / (L - 1). From cooked levels, `options` is not used, and the chain's
// minMaxDistance is left empty (the asset stores each level's min distance in A, no max;
// nothing the lookups read needs it). Throws Error naming the manifest when the asset has no
// composite or a cooked level's faces are not max(1, faceRes >> i) square RGBA.
CubeChain glossyChainOf(const DistanceProbeAsset& asset, const GgxPrefilterOptions& options = {});

} // namespace specula
