#include "assetcooker/lib/cli/setting_text.h"

#include "engine/core/error.h"

namespace specula::cook {

std::string settingRangeCheck(double v, const SettingInfo& info) {
    if (v >= info.lo && v <= info.hi) return {};
    std::ostringstream s;
    s << "expected " << settingRange(info) << ", got " << v;
    return s.str();
}

int settingWordIndex(const std::string& text, const SettingInfo& info) {
    for (std::size_t i = 0; i < info.words.size(); ++i)
        if (text == info.words[i]) return int(i);
    return -1;
}

std::string settingWordsExpected(const std::string& text, const SettingInfo& info) {
    return "expected " + settingWords(info) + ", got '" + text + "'";
}

std::string SettingText<glm::vec3>::parse(const std::string& text, const SettingInfo&,
                                          glm::vec3& v) {
    try {
        v = cli::parseVec3(text);
        return {};
    } catch (const Error& e) {
        return e.message();
    }
}

std::string SettingText<ErrorBudget>::parse(const std::string& text, const SettingInfo& info,
                                            ErrorBudget& v) {
    try {
        v = parseErrorBudget(text, "", info.flag ? info.flag : "");
        return {};
    } catch (const Error& e) {
        return e.message();
    }
}

} // namespace specula::cook
