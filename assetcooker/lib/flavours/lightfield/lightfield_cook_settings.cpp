#include "assetcooker/lib/flavours/lightfield/lightfield_cook_settings.h"

namespace specula {

void checkCookSettings(const LightFieldCookSettings& s, const std::string& file) {
    if (s.cameras * s.imageRes > 16384)
        throw Error(file, "cameras",
                    "NUM x image_res RES = " + std::to_string(s.cameras * s.imageRes) +
                        " exceeds 16384 (the 2D texture side)");
}

} // namespace specula
