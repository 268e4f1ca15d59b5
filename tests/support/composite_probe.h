#pragma once
// A scene cooked as one unplanned distance probe (the composite alone, no object layers) at
// `faceRes`, read back from a scratch folder named after `tag` and the process, which is
// removed again: the asset the CPU-twin lookup tests search.
#include "assetcooker/lib/bake/cook.h"
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "support/probe_room.h"

#include <filesystem>
#include <string>
#include <unistd.h>

namespace specula::test {

inline DistanceProbeAsset cookedCompositeProbe(ProbeRoom& room, int faceRes,
                                               const std::string& tag) {
    const std::string dir =
        (std::filesystem::temp_directory_path() / (tag + "-" + std::to_string(::getpid())))
            .string();
    DistanceCookSettings s;
    s.faceRes = faceRes;
    s.planned = s.recordPlan = false;
    CookOptions o;
    o.out = dir;
    o.flavour = s;
    o.progress = false;
    cookProbe(room.probeScene(), o, nullptr);
    DistanceProbeAsset asset = readDistanceProbe(dir + "/manifest.json");
    std::filesystem::remove_all(dir);
    return asset;
}

} // namespace specula::test
