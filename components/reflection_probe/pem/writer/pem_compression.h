#pragma once
// Compressing a PEM probe's distant maps to BC6H (`specula-cook bake --flavour pem --compress
// bc6h`, PemCompression::Bc6h): the tools' side; the runtime reads and uploads the blocks.
#include "components/reflection_probe/pem/pem_asset.h"

#include <string>
#include <vector>

namespace specula {

// Encodes every level of every sample's distant map (engine/image/bc6h.h, each face on its
// own), keeps the blocks in the sample and replaces its texels by their decoding: the asset as
// the compressed probe holds it, so the CPU twin measures what compression costs. Samples are
// encoded in parallel. The local layer and the distance cube are left as they are (float). An
// asset already compressed is left as it is.
void compressPemMaps(PemAsset& asset);

// That every sample's blocks decode to exactly its texels (the writer's check before a
// compressed asset is written; `files[k]` names sample k's file in the error, "radiance").
void checkPemBlocks(const PemAsset& asset, const std::vector<std::string>& files);

} // namespace specula
