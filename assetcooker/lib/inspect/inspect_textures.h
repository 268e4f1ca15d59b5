#pragma once
// `specula-cook inspect` of cooked textures: what every KTX2 file of a probe or level folder
// (or one .ktx2 file) holds, and the debug dump of them as OpenEXR (`--dump-exr DIR`), the
// format a texture viewer opens. Cooked probes store KTX2 only (docs/formats.md).
#include <nlohmann/json.hpp>

#include <string>

namespace specula::cook {

// Whether `path` names cooked textures (a folder, or a .ktx2 file) rather than a glTF scene.
bool isCookedTexturePath(const std::string& path);

// {"path", "textures": [{"file", "format", "cube", "width", "height", "levels", "bytes"}],
// "bytes"}: every .ktx2 under `path` (a folder, searched recursively, in path order) or
// `path` itself. With a non-empty `exrDir`, also writes each texture's levels as
// <exrDir>/<file without .ktx2>[_mipK].exr (a cube level as its N x 6N strip of faces, BC6H
// decoded) and lists them under "exr". Throws Error naming the file that cannot be read, or
// the folder when it holds no .ktx2.
nlohmann::json inspectTextures(const std::string& path, const std::string& exrDir = "");

} // namespace specula::cook
