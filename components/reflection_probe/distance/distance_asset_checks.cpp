// The content checks of a cooked distance probe: what its images hold against what its
// manifest states (figures, layer order, glossy levels, sky). The reader runs them after
// reading and the writer before writing (distance_probe_asset.cpp).
#include "distance_asset_internal.h"

#include "engine/core/error.h"

#include <algorithm>
#include <cmath>

namespace specula::distance_asset {

bool radianceOk(const float* rgb) {
    return rgb[0] >= 0.f && rgb[0] <= kMaxRadiance && rgb[1] >= 0.f && rgb[1] <= kMaxRadiance &&
           rgb[2] >= 0.f && rgb[2] <= kMaxRadiance; // false for NaN too
}

// Throws for the first RGB channel that is not finite in [0, kMaxRadiance].
void refuseRadiance(const float* p, const std::string& file, const std::string& where) {
    for (int c = 0; c < 3; ++c)
        if (!(p[c] >= 0.f && p[c] <= kMaxRadiance))
            throw Error(file, "radiance",
                        where + " channel " + "RGB"[c] + " holds " + shortNumber(p[c]) +
                            "; expected a finite radiance in [0, " + shortNumber(kMaxRadiance) +
                            "]");
}

namespace {

// The manifest's figures for a layer against what its image holds. A layer file swapped with
// another (checksums and all) or edited (checksum updated) fails here.
void checkFigures(const DistanceProbeLayer& L, const DistanceLayerContent& c,
                  const std::string& manifest, const std::string& path, const std::string& image) {
    // Distances pass float -> JSON -> float exactly; the margin only absorbs a writer that
    // rounds. Solid angles are sums over texels: 1e-3 sr absorbs a writer's own rounding
    // (and the 12.566 some tools write for 4 pi) while a swapped layer differs by whole texels.
    auto mismatch = [&](const char* key, double stored, double measured, const char* what) {
        throw Error(manifest, path + key,
                    "says " + shortNumber(stored) + " but " + image + " holds " +
                        shortNumber(measured) + " (" + what +
                        "); the layer file was swapped or edited");
    };
    const double tol = 1e-5 * std::max(1.0, double(c.maxDistance));
    if (std::fabs(double(L.minDistance) - c.minDistance) > tol)
        mismatch("min_distance", L.minDistance, c.minDistance, "its nearest hit");
    if (std::fabs(double(L.maxDistance) - c.maxDistance) > tol)
        mismatch("max_distance", L.maxDistance, c.maxDistance, "its farthest hit");
    if (std::fabs(double(L.solidAngle) - c.solidAngle) > 1e-3 + 1e-4 * c.solidAngle)
        mismatch("solid_angle_sr", L.solidAngle, c.solidAngle, "steradians it hits");
    if (c.solidAngle > 0.0 &&
        !(L.avgDistance >= c.minDistance - tol && L.avgDistance <= c.maxDistance + tol))
        throw Error(manifest, path + "avg_distance",
                    "says " + shortNumber(L.avgDistance) + ", outside the layer's own range [" +
                        shortNumber(c.minDistance) + ", " + shortNumber(c.maxDistance) + "]");
}

// Layer 0, the composite of the whole environment, is per texel the nearest of the object
// layers (each object layer sees a subset of the same geometry, so never nearer). A layer
// swapped with the composite fails here even when its manifest entry moved with it.
void checkCompositeNearest(const DistanceProbeAsset& a, const std::string& manifest,
                           const std::vector<std::string>& files) {
    const int n = a.faceRes;
    for (std::size_t k = 1; k < a.layers.size(); ++k)
        for (int f = 0; f < 6; ++f)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    const float d0 = a.layers[0].faces[std::size_t(f)].at(x, y)[3];
                    const float dk = a.layers[k].faces[std::size_t(f)].at(x, y)[3];
                    // 1e-3: the same hit traced through two acceleration structures, and an
                    // object layer stored as half floats (11 bits: within 2.5e-4 of it) beside
                    // the float composite. A swapped layer differs by far more.
                    if (d0 <= dk * (1.f + 1e-3f)) continue;
                    throw Error(manifest, "layers[0]",
                                "the composite (" + files[0] + ") is farther than layers[" +
                                    std::to_string(k) + "] (" + files[k] + ") at " +
                                    texelName(f, x, y) + ": " + shortNumber(d0) + " vs " +
                                    shortNumber(dk) +
                                    "; layer 0 must be the nearest of the object layers "
                                    "(layers swapped?)");
                }
}

} // namespace

void checkContent(const DistanceProbeAsset& a, const std::string& manifest,
                  const std::vector<std::string>& files,
                  const std::vector<std::string>& glossyFiles, const std::string& skyFile) {
    if (a.layers.empty()) throw Error(manifest, "layers", "expected at least the composite");
    const std::vector<float> solidAngles = faceSolidAngles(a.faceRes);
    for (std::size_t i = 0; i < a.layers.size(); ++i) {
        const DistanceProbeLayer& L = a.layers[i];
        if (L.faces[0].width != a.faceRes)
            throw Error(files[i], "size",
                        "expected faces of " + std::to_string(a.faceRes) + " texels, got " +
                            std::to_string(L.faces[0].width));
        const DistanceLayerContent c = scanLayer(L.faces, a.dInf, solidAngles, files[i]);
        checkFigures(L, c, manifest, "layers[" + std::to_string(i) + "].", files[i]);
    }
    checkCompositeNearest(a, manifest, files);
    checkGlossy(a, manifest, glossyFiles);
    if (a.sky.empty()) return;
    const int channels = std::min(a.sky.channels, 3);
    for (int y = 0; y < a.sky.height; ++y)
        for (int x = 0; x < a.sky.width; ++x) {
            const float* p = a.sky.at(x, y);
            const float rgb[3] = {p[0], channels > 1 ? p[1] : p[0], channels > 2 ? p[2] : p[0]};
            if (!radianceOk(rgb))
                refuseRadiance(rgb, skyFile,
                               "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")");
        }
}

} // namespace specula::distance_asset
