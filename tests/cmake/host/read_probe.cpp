// A host's program, built against Specula::runtime alone (by the parent-project and the
// installed-package tests): reads a cooked distance probe and looks up what a mirror at its
// centre reflects along +X through the CPU twin of the shader, with the method the cooker
// planned. Prints "face_res N layers L radiance R G B"; a bad asset is an error message
// naming the file, exit status 1.
#include "components/reflection_probe/distance/distance_lookup_config.h"
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "components/reflection_probe/distance/distance_probe_cpu.h"
#include "engine/core/error.h"

#include <cmath>
#include <cstdio>

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: read_probe MANIFEST\n");
        return 2;
    }
    try {
        const specula::DistanceProbeAsset asset = specula::readDistanceProbe(argv[1]);
        const specula::CpuDistanceProbe probe(
            asset, specula::makeLookupConfig(specula::DistanceProbe{}, asset));
        int fetches = 0;
        const glm::vec3 c = probe.radiance(glm::vec3(0.f), glm::vec3(1.f, 0.f, 0.f), fetches);
        std::printf("face_res %d layers %zu radiance %g %g %g\n", asset.faceRes,
                    asset.layers.size(), c.r, c.g, c.b);
        return std::isfinite(c.r + c.g + c.b) ? 0 : 1;
    } catch (const specula::Error& e) {
        std::fprintf(stderr, "read_probe: %s\n", e.what());
        return 1;
    }
}
