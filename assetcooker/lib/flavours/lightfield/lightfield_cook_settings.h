#pragma once
// The light-field-slab flavour's cooking settings, each declared once (settings/setting.h):
// the bake's flags, the shard list's JSON and the level's options checksum all come from
// visitSettings below.
#include "assetcooker/lib/settings/setting.h"
#include "components/reflection_probe/lightfield/lightfield_asset.h"

#include <optional>
#include <string>
#include <type_traits>

#include <glm/vec3.hpp>

namespace specula {

// The cell defaults to the probe markup's (cell_size, else 1.5 m) around the probe centre.
struct LightFieldCookSettings {
    static constexpr const char* kFlavour = "lightfield";
    std::optional<glm::vec3> cellCentre;
    std::optional<float> cellSize;
    int cameras = 8, imageRes = 64;
    LightFieldCompression compression = LightFieldCompression::None;
};

template <class S, class V>
requires std::is_same_v<std::remove_const_t<S>, LightFieldCookSettings>
void visitSettings(S& s, V&& visit) {
    visit({.key = "cell_centre",
           .flag = "--cell-center",
           .help = "cell centre in world space (default: the probe position)",
           .optional = true},
          s.cellCentre);
    visit({.key = "cell_size",
           .flag = "--cell-size",
           .help = "cell side in metres (default: the probe's cell_size, else 1.5)",
           .lo = 1e-3,
           .hi = 1e4,
           .optional = true},
          s.cellSize);
    visit({.key = "cameras",
           .flag = "--cameras",
           .help = "cameras per side of a slab",
           .lo = 2,
           .hi = 256},
          s.cameras);
    // BC1 blocks (4x4 texels) must not straddle two cameras of an atlas.
    visit({.key = "image_res",
           .flag = "--image-res",
           .help = "pixels per side of a camera image",
           .lo = 4,
           .hi = 4096,
           .multipleOf = 4},
          s.imageRes);
    visit({.key = "compression",
           .flag = "--compress",
           .help = "none (sRGB RGB8) or bc1 (DXT1; bc7 is not supported: no BC7 encoder)",
           .words = {"none", "bc1"}},
          s.compression);
}

// Refuses settings no bake can run: an atlas side (cameras x image_res) past 16384, the
// 2D texture side. Throws Error(file, "cameras", ...).
void checkCookSettings(const LightFieldCookSettings& s, const std::string& file);

} // namespace specula
