// Every flavour's settings are declared once (visitSettings, settings/setting.h) and the
// settings JSON (shard list, recorded inputs, a level's options checksum) is derived from
// that list: a change of any one leaf setting, of any flavour, changes the JSON and reads
// back as it was written. Each leaf is changed in turn by a generic edit, so a setting added
// to a flavour is covered without an edit here.
#include "assetcooker/lib/bake/cook_settings_json.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <type_traits>

namespace specula {
namespace {

// A value of `v`'s type other than `v`, within the setting's range and words.
template <class T> void changeOne(const SettingInfo& info, T& v) {
    if constexpr (std::is_same_v<T, bool>) {
        v = !v;
    } else if constexpr (std::is_enum_v<T>) {
        v = T((std::size_t(v) + 1) % info.words.size());
    } else if constexpr (std::is_same_v<T, std::string>) {
        if (info.words.empty()) {
            v += "-changed";
            return;
        }
        for (std::size_t i = 0; i < info.words.size(); ++i)
            if (v == info.words[i]) {
                v = info.words[(i + 1) % info.words.size()];
                return;
            }
        v = info.words.front();
    } else if constexpr (std::is_arithmetic_v<T>) {
        if constexpr (std::is_floating_point_v<T>)
            if (!std::isfinite(v)) {
                v = T(100);
                return;
            }
        const double lo = std::isfinite(info.lo) ? info.lo : -1e6;
        const double hi = std::isfinite(info.hi) ? info.hi : 1e6;
        const double step = info.multipleOf;
        for (double c : {double(v) + step, double(v) - step, (lo + double(v)) / 2,
                         (hi + double(v)) / 2, lo, hi})
            if (c >= lo && c <= hi && T(c) != v &&
                (!std::is_integral_v<T> || std::fmod(c, step) == 0.0)) {
                v = T(c);
                return;
            }
        FAIL() << info.key << ": no other value in range";
    } else if constexpr (std::is_same_v<T, glm::vec3>) {
        v += glm::vec3(1.f);
    } else if constexpr (std::is_same_v<T, ErrorBudget>) {
        v = ErrorBudget{ErrorBudget::Kind::Psnr, v.value + 30.0, "test"};
    }
}

template <class T> struct IsOptional : std::false_type {};
template <class T> struct IsOptional<std::optional<T>> : std::true_type {};

// Changes the `target`-th leaf setting of `s` (nested settings count their own leaves);
// `count` ends as the number of leaves.
template <class S> void changeLeaf(S& s, int target, int& count) {
    visitSettings(s, [&](const SettingInfo& info, auto&& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (JsonSetting<T>) {
            if (!info.key) return;
            if constexpr (NestedSettings<T>) {
                changeLeaf(v, target, count);
            } else {
                if (count++ != target) return;
                if constexpr (IsOptional<T>::value) {
                    if (!v) {
                        typename T::value_type x{};
                        if constexpr (std::is_arithmetic_v<typename T::value_type>)
                            x = typename T::value_type(std::isfinite(info.lo) ? info.lo : 1);
                        v = x;
                        if constexpr (std::is_same_v<typename T::value_type, ErrorBudget>)
                            changeOne(info, *v);
                    } else {
                        changeOne(info, *v);
                    }
                } else {
                    changeOne(info, v);
                }
            }
        }
    });
}

TEST(CookSettingsDeclaration, EveryLeafOfEveryFlavourReachesTheJsonAndReadsBack) {
    int flavours = 0;
    forEachCookFlavour([&](const auto& defaults) {
        using S = std::decay_t<decltype(defaults)>;
        ++flavours;
        const nlohmann::json base = cookSettingsToJson(CookFlavour{defaults});
        EXPECT_EQ(base.at("flavour"), S::kFlavour);
        S probe = defaults;
        int leaves = 0;
        changeLeaf(probe, -1, leaves); // counts the leaves, changes none
        ASSERT_GT(leaves, 2) << S::kFlavour;
        for (int i = 0; i < leaves; ++i) {
            S s = defaults;
            int count = 0;
            changeLeaf(s, i, count);
            const nlohmann::json j = cookSettingsToJson(CookFlavour{s});
            EXPECT_NE(j, base) << S::kFlavour << " leaf " << i << " is not in the JSON";
            S back = defaults;
            settingsFromJson(j, back, "settings.json", "settings.");
            EXPECT_EQ(cookSettingsToJson(CookFlavour{back}), j)
                << S::kFlavour << " leaf " << i << " does not read back";
        }
    });
    EXPECT_EQ(flavours, int(std::variant_size_v<CookFlavour>));
}

TEST(CookSettingsDeclaration, DefaultsReadBackThroughTheCheckedReader) {
    forEachCookFlavour([&](const auto& defaults) {
        using S = std::decay_t<decltype(defaults)>;
        const nlohmann::json j = cookSettingsToJson(CookFlavour{defaults});
        const CookFlavour back = cookSettingsFromJson(j, "settings.json");
        ASSERT_TRUE(std::holds_alternative<S>(back)) << S::kFlavour;
        EXPECT_EQ(cookSettingsToJson(back), j);
    });
}

TEST(CookSettingsDeclaration, AMissingOrWrongMemberNamesTheField) {
    nlohmann::json j = cookSettingsToJson(CookFlavour{LightFieldCookSettings{}});
    j.erase("cameras");
    try {
        (void)cookSettingsFromJson(j, "shards.json");
        FAIL() << "a missing member was read";
    } catch (const Error& e) {
        EXPECT_EQ(e.field(), "settings.cameras");
    }
    j = cookSettingsToJson(CookFlavour{DistanceCookSettings{}});
    j["glossy"] = "sometimes";
    try {
        (void)cookSettingsFromJson(j, "shards.json");
        FAIL() << "an unknown word was read";
    } catch (const Error& e) {
        EXPECT_EQ(e.field(), "settings.glossy");
        EXPECT_NE(std::string(e.what()).find("auto, on or off"), std::string::npos) << e.what();
    }
    j = cookSettingsToJson(CookFlavour{DistanceCookSettings{}});
    j["face_res"] = 0;
    EXPECT_THROW((void)cookSettingsFromJson(j, "shards.json"), Error); // out of 1 .. 4096
    j["flavour"] = "hologram";
    EXPECT_THROW((void)cookSettingsFromJson(j, "shards.json"), Error);
}

} // namespace
} // namespace specula
