#pragma once
// Decoding of the 8-bit PNG/JPEG textures glTF carries into linear float RGBA.
#include "engine/image/image.h"

#include <cstddef>
#include <optional>
#include <string>

namespace specula {

// Decodes an encoded PNG or JPEG. `srgb` selects the sRGB transfer function for the colour
// channels (base colour textures); alpha is always linear. On failure returns nullopt and
// says why in `whyNot`.
std::optional<Image> decodeTexture8(const unsigned char* bytes, std::size_t size, bool srgb,
                                    std::string& whyNot);

// The sRGB electro-optical transfer function for one 8-bit code value.
float srgb8ToLinear(unsigned char code);

} // namespace specula
