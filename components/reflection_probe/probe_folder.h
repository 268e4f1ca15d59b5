#pragma once
// Writing a cooked probe folder so that nothing is ever half-written: `fill` writes every
// file into a sibling temporary folder and returns the manifest; the manifest goes last and
// the finished folder replaces DIR by rename. On any failure DIR is left as it was and the
// temporary folder is removed. DIR may only be a cooked probe (a folder with manifest.json)
// or an empty folder: a mistyped --out never replaces a file or someone's folder.
#include <filesystem>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

namespace specula {

void writeProbeFolder(const std::string& dir,
                      const std::function<nlohmann::json(const std::filesystem::path& tmp)>& fill);

} // namespace specula
