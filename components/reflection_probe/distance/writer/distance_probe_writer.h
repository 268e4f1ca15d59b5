#pragma once
// Writing a cooked distance probe: the tools' side of distance_probe_asset.h (the runtime reads,
// the cooker and the tests write). The manifest, the layer KTX2s, a compressed composite's BC6H
// radiance and distance cubes and the glossy levels, all through writeProbeFolder.
#include "components/reflection_probe/distance/distance_probe_asset.h"

#include <string>

namespace specula {

// Writes DIR/manifest.json, the layer KTX2s and the glossy levels' KTX2s. Everything goes to a
// sibling temporary folder first and replaces DIR by rename, so an interrupted or failed
// write leaves DIR as it was. The reader's content checks run first: a probe its reader would
// refuse is never written.
void writeDistanceProbe(const DistanceProbeAsset& asset, const std::string& dir,
                        const std::string& sourceScene);

} // namespace specula
