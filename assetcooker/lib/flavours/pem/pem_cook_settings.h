#pragma once
// The PEM flavour's cooking settings, each declared once (settings/setting.h): the bake's
// flags, the shard list's JSON and a probe's recorded settings all come from visitSettings
// below.
#include "assetcooker/lib/settings/setting.h"
#include "components/reflection_probe/pem/pem_asset.h"

#include <string>
#include <type_traits>

namespace specula {

// The PEM flavour's cook settings (cook.h's CookFlavour). Parameter "viewpoint": the camera
// moves along the walk's camera orbit (path "orbit", walkOrbitCameraView), the reflectors stay
// put. Parameter "reflector": the reflectors move along the walk path "orbit", "line" or
// "figure8" (walk_path.h) before the scene camera (the orbit at t = 0): the paper's "relative
// motion of objects". Path "camera" (a glTF camera animation) is refused: not read yet.
struct PemCookSettings {
    static constexpr const char* kFlavour = "pem";
    int samples = 8;     // parameter samples t = k / samples, k = 0 .. samples-1; 1 .. 1024
    int faceRes = 128;   // 1 .. 1024
    int supersample = 1; // rays per pixel side, 1 .. 16
    float regularisation = 0.02f;
    // The map's geometry: "box" (the ray meets the environment's bounding box) or "distance"
    // (the ray is rectified against the environment's distance cube at the centre, traced
    // by Embree at faceRes: objects inside the box sit where they are, from any viewpoint).
    std::string geometry = "distance";
    // Weight of the rows pulling every texel towards the radiance captured at the centre
    // (the distance geometry's capture): texels the camera does not see fall back to what
    // an ordinary cube map holds there instead of to their neighbours alone. 0: no prior.
    // 0.05 measured on the room (320x240, 8 viewpoints): half-way 18.4 -> 19.7 dB full,
    // on the samples 46.3 -> 41.3 dB.
    float priorWeight = 0.05f;
    std::string parameter = "viewpoint";
    std::string path = "orbit";
    // The camera image the samples are traced through: a PEM is inferred for the pixels the
    // renderer draws, so bake at the frame size it will be drawn at (the walk's default
    // 640 x 480). With supersample 1 the rows are exactly the rasteriser's pixel centres.
    int imageWidth = 640, imageHeight = 480;
    // The local layer (pem_layers.h): "auto" adds it when some reflector ray off the hull
    // meets its own reflector again at any sample (measured), "on" always, "off" never.
    std::string localLayer = "auto";
    int localFaceRes = 0; // its cube's face resolution; 0: faceRes
    // The local sphere: "bound" (the off-hull reflector points' bounding sphere) or "fit" (the
    // least-squares sphere through them: a bowl's own sphere; fitPemLocalSphere). Measured on
    // the bowl room (N=8, on / half-way dB against the full truth, cooker's fit): 160x120 with
    // 64^2 faces bound 29.3 / 13.1, fit 28.9 / 13.3 (one map 28.2 / 13.1); 120x90 with 24^2
    // faces bound 28.0 / 13.8, fit 24.4 / 13.3 (one map 21.0 / 12.9). Rays from different
    // points that meet the bowl at one point see different things there; the exact sphere
    // sends them all to one texel, a sphere off the bowl's centre spreads them.
    std::string localSphere = "bound";
    // MIP levels of the distant maps, all inferred together (PemInferOptions::mipLevels), 1 ..
    // PemMap::maxLevels(faceRes); 1: level 0 alone, as before MIP levels existed.
    int mipLevels = 1;
    // The rendering matrix's data rows (PemRows), against the antialiased image (each
    // displayed pixel's mean radiance over its sub-rays, Hakura §4): "pixel", the mean of
    // the sub-rays' lookups; "centre" (an odd supersample), the lookup of the pixel's centre
    // ray, as the rasteriser draws it; or "subray", one row per traced ray against its own
    // radiance (the default: the bench's truth is one ray a pixel, against which centre rows
    // lose on level 0 while they win against the antialiased image, pem_pixel_rows_test).
    // All the same with supersample 1.
    std::string rows = "subray";
    // Keep the inferred texels >= 0 by active-set re-solves (PemInferOptions::nonNegative)
    // instead of clamping the unconstrained solution afterwards. On by default: at 256² the
    // full PSNR gains 0-0.3 dB at level 0 and 1.6-3.1 dB with inferred MIPs, the cooker's own
    // fit 10-15 dB, for 1.5-1.9x the inference (CHANGELOG.md, "PEM texels bounded ... at 256²").
    bool nonNegative = true;
    // Distance geometry: rows for the lookups the display's rounding reaches
    // (pem_rounding_rows.h; PemInferOptions::roundingReach), metres and radians. 0: off.
    float roundingReach = 1e-4f;
    // How the maps are stored: "none" (float RGB) or "bc6h" (every level of every sample map in
    // BC6H, pem/writer/pem_compression.h), encoded after the inference.
    std::string compression = "none";
};

template <class S, class V>
requires std::is_same_v<std::remove_const_t<S>, PemCookSettings>
void visitSettings(S& s, V&& visit) {
    visit({.key = "samples",
           .flag = "--samples",
           .help = "parameter samples: one inferred map per viewpoint t = k/N",
           .lo = 1,
           .hi = kMaxPemSamples},
          s.samples);
    visit({.key = "face_res",
           .flag = "--face-res",
           .help = "cube face resolution",
           .lo = 1,
           .hi = 1024},
          s.faceRes);
    visit({.key = "supersample",
           .flag = "--supersample",
           .help = "S x S rays per reflector pixel (1: the pixel centres the rasteriser shades)",
           .lo = 1,
           .hi = 16},
          s.supersample);
    visit({.key = "regularisation",
           .flag = "--smoothness",
           .help = "weight of the rows tying every texel to its neighbours",
           .lo = 0,
           .hi = 100},
          s.regularisation);
    visit({.key = "geometry",
           .flag = "--geometry",
           .help = "the maps' geometry: distance (rectified against the environment's distance "
                   "cube, traced at the face resolution) or box (the environment's bounding "
                   "box)",
           .words = {"box", "distance"}},
          s.geometry);
    visit({.key = "prior_weight",
           .flag = "--prior",
           .help = "distance geometry: weight pulling texels towards the radiance captured at "
                   "the centre, where the camera sees nothing (0: none)",
           .lo = 0,
           .hi = 100},
          s.priorWeight);
    visit({.key = "parameter",
           .flag = "--parameter",
           .help = "what the maps vary with: viewpoint (the camera moves) or reflector (the "
                   "reflectors move before the scene camera)",
           .words = {"viewpoint", "reflector"}},
          s.parameter);
    visit({.key = "path",
           .flag = "--path",
           .help = "the path the parameter runs along: orbit (the walk's camera orbit, or the "
                   "reflectors' orbit), line or figure8 (reflector only); camera (viewpoint "
                   "only: the scene camera's glTF animation, first key to last, an open path "
                   "whose two ends are samples)"},
          s.path);
    visit({.key = "image_width", .lo = 16, .hi = 8192}, s.imageWidth);
    visit({.key = "image_height", .lo = 16, .hi = 8192}, s.imageHeight);
    visit({.flag = "--image-size",
           .help = "the camera image the maps are inferred for: bake at the frame size they "
                   "will be drawn at (the walk's)"},
          ImageSizeSetting{s.imageWidth, s.imageHeight});
    visit({.key = "local_layer",
           .flag = "--local-layer",
           .help = "the local layer (what a concave reflector shows of itself, over the distant "
                   "map off the reflector's hull): auto (where reflector rays meet their own "
                   "reflector again, measured), on or off",
           .words = {"auto", "on", "off"}},
          s.localLayer);
    visit({.key = "local_face_res", .lo = 0, .hi = 1024}, s.localFaceRes);
    visit({.key = "local_sphere", .words = {"bound", "fit"}}, s.localSphere);
    visit({.key = "mip_levels",
           .flag = "--mip-levels",
           .help = "MIP levels of the distant maps, every level inferred together (the paper's "
                   "MIP inference; the shader picks the level from the pixel's footprint): 1 .. "
                   "log2(face res) + 1",
           .lo = 1,
           .hi = 16},
          s.mipLevels);
    visit({.key = "rows",
           .flag = "--rows",
           .help = "the rendering matrix's rows against the antialiased image (each pixel's "
                   "mean radiance over its --supersample sub-rays): pixel (the mean of the "
                   "sub-rays' lookups), centre (the lookup of the pixel's centre ray, as the "
                   "rasteriser draws it; odd --supersample), or subray (one row per traced ray "
                   "against its own radiance)",
           .words = {"pixel", "centre", "subray"}},
          s.rows);
    visit({.key = "non_negative",
           .flag = "--non-negative",
           .help = "keep the inferred texels >= 0 (and the local layer's coverage in [0, 1]) by "
                   "re-solving with the crossing texels pinned at the bound, instead of clamping "
                   "afterwards: on or off",
           .words = {"off", "on"}},
          s.nonNegative);
    visit({.key = "rounding_reach",
           .flag = "--rounding-reach",
           .help = "distance geometry: where moving a reflector ray's point or direction by this "
                   "much (metres; radians) along an axis makes the search end on other texels, "
                   "the moved ray becomes a row too, so the display, whose interpolants differ "
                   "from the tracer's by rounding, reads fitted texels (0: off)",
           .lo = 0,
           .hi = 0.01},
          s.roundingReach);
    visit({.key = "compression",
           .flag = "--compress",
           .help = "none (float RGB maps) or bc6h (every sample map and MIP level in BC6H: asset "
                   "format 3.2)",
           .words = {"none", "bc6h"},
           .optional = true},
          s.compression);
}

// Throws Error naming the field ("samples", "face_res", "supersample", "regularisation",
// "image_size", "geometry", "prior_weight" (needs the distance geometry), "parameter", "path"
// (orbit or camera for the viewpoint, a walk path for the reflector),
// "local_layer", "local_face_res", "local_sphere", "mip_levels", "rows").
void validatePemCookSettings(const PemCookSettings& s, const std::string& file);
inline void checkCookSettings(const PemCookSettings& s, const std::string& file) {
    validatePemCookSettings(s, file);
}

} // namespace specula
