#pragma once
// Writing a cooked PEM probe: the tools' side of pem_asset.h (the runtime reads, the cooker and
// the tests write).
#include "components/reflection_probe/pem/pem_asset.h"

#include <string>

namespace specula {

// Writes DIR/manifest.json, sample_NN.ktx2 (and distance.ktx2) through writeProbeFolder (atomic:
// DIR is replaced by one rename or left as it was). The reader's checks run first, so a probe the
// reader would refuse is never written; they throw Error naming DIR's manifest (or a sample's file)
// and the field: "centre", "parameter_kind", "path", "face_res", "box", "geometry", "distance.*"
// (checkPemDistanceGeometry; distance.ktx2 for the distances), "samples",
// "samples[k].parameter", "samples[k].map" (size, box or geometry unlike the asset's),
// "radiance", "mip_levels", "local_layer.*" (face_res, centre, radius), "samples[k].local" (the
// local map unlike the asset's layer), "alpha" (a local map's coverage outside [0, 1]).
void writePemProbe(const PemAsset& asset, const std::string& dir, const std::string& sourceScene);

} // namespace specula
