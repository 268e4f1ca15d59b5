#pragma once
// What the PEM probe's reader (pem_asset.cpp) and writer (writer/pem_probe_writer.cpp) share:
// the file names, how maps are stacked into KTX2 cubes, and the whole-asset check the writer
// runs before writing. Not part of the component's API: only those files include it.
#include "components/reflection_probe/pem/pem_asset.h"
#include "engine/image/image.h"

#include <string>
#include <vector>

namespace specula::pem_asset {

inline constexpr const char* kDistanceFile = "distance.ktx2";

std::string sampleFileName(std::size_t k); // sample_NN.ktx2
std::string localFileName(std::size_t k);  // local_NN.ktx2
// A local map stacked as the distant ones, RGBA: premultiplied RGB and coverage.
Image stackLocal(const PemMap& m);
// The distance cube's faces stacked as the maps' are, one channel.
Image stackDistances(const PemDistanceGeometry& g);
// What the reader checks of the whole asset; the writer runs it first too. `files[k]` names
// sample k's image, `distanceFile` the distance cube's, `localFiles[k]` its local map's.
void checkAsset(const PemAsset& a, const std::string& manifest,
                const std::vector<std::string>& files, const std::string& distanceFile,
                const std::vector<std::string>& localFiles);

} // namespace specula::pem_asset
