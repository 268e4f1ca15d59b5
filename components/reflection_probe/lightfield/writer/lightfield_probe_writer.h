#pragma once
// Writing a cooked light-field probe: the tools' side of lightfield_asset.h (the runtime reads,
// the cooker and the tests write).
#include "components/reflection_probe/lightfield/lightfield_asset.h"

#include <string>

namespace specula {

// Writes DIR/manifest.json and the six slab files, atomically (temporary folder + rename).
void writeLightFieldProbe(const LightFieldAsset& asset, const std::string& dir,
                          const std::string& sourceScene);

} // namespace specula
