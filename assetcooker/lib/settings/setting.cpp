#include "assetcooker/lib/settings/setting.h"

#include "components/reflection_probe/probe_volume.h"

#include <sstream>

namespace specula {

std::string settingRange(const SettingInfo& info) {
    std::ostringstream s;
    s << info.lo << " .. " << info.hi;
    return s.str();
}

std::string settingWords(const SettingInfo& info) {
    std::string out;
    for (std::size_t i = 0; i < info.words.size(); ++i)
        out += (i == 0                       ? ""
                : i + 1 == info.words.size() ? " or "
                                             : ", ") +
               std::string(info.words[i]);
    return out;
}

std::string SettingJson<std::string>::read(const nlohmann::json& j, const SettingInfo& info,
                                           const std::string& file, const std::string& field) {
    if (!j.is_string()) throw Error(file, field, "expected a string");
    const std::string v = j.get<std::string>();
    if (info.words.empty()) return v;
    for (const char* w : info.words)
        if (v == w) return v;
    throw Error(file, field, "expected " + settingWords(info) + ", got '" + v + "'");
}

glm::vec3 SettingJson<glm::vec3>::read(const nlohmann::json& j, const SettingInfo&,
                                       const std::string& file, const std::string& field) {
    return probeVec3(j, file, field);
}

} // namespace specula
