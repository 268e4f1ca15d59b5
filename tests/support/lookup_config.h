#pragma once
// What a distance probe with these settings runs over asset `a` (makeLookupConfig): the
// method, its tolerance d_e and, in layered mode, the object layers' method (Envmap: each
// layer's cooked one, the manifest's "method").
#include "components/reflection_probe/distance/distance_lookup_config.h"
#include "components/reflection_probe/distance/distance_probe.h"

namespace specula::test {

inline DistanceLookupConfig lookupConfigOf(const DistanceProbeAsset& a, DistanceMethod method,
                                           float de,
                                           DistanceMethod layerMethod = DistanceMethod::Envmap) {
    DistanceProbe p;
    p.method = method;
    p.layerMethod = layerMethod;
    p.errorTolerance = de;
    return makeLookupConfig(p, a);
}

} // namespace specula::test
