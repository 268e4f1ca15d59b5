#pragma once
// One setting of a flavour's cooking, declared once. A flavour's settings struct lists its
// fields in one function, visitSettings(settings, visit), calling visit(info, member) for
// each: its key in the settings JSON (the shard list, a cooked probe's recorded inputs and a
// level's options checksum), its flag (also its `--config` key), its help and what it
// accepts. The JSON below and the command line (cli/setting_flags.h) are derived from that
// list, so no field can be left out of either, and a field's default is its initialiser.
#include "engine/core/error.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <concepts>
#include <cstdint>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include <glm/vec3.hpp>

#include <limits>

namespace specula {

struct SettingInfo {
    const char* key = nullptr;  // settings.<key> in the JSON; nullptr: the command line's only
    const char* flag = nullptr; // "--face-res"; nullptr: not on the command line
    const char* help = "";
    // A bool's words {false, true}; an enum's, one per value in order; a string's choices
    // (none: any text).
    std::vector<const char*> words = {};
    double lo = -HUGE_VAL, hi = HUGE_VAL; // a number's accepted range
    int multipleOf = 1;                   // an integer's step (BC1 blocks: 4)
    // Missing from the JSON written before the setting existed: its default.
    bool optional = false;
};

// Two integers one flag sets as WIDTHxHEIGHT (a camera image): on the command line only, the
// JSON holds each under its own key.
template <class I> struct ImageSizeSetting {
    I& width;
    I& height;
};
template <class I> ImageSizeSetting(I&, I&) -> ImageSizeSetting<I>;

// Settings nested as a JSON object (visitSettings of their own, no flags).
template <class T>
concept NestedSettings = requires(T& t) {
    visitSettings(t, [](const SettingInfo&, auto&&) {});
};

// "1 .. 4096", for messages.
std::string settingRange(const SettingInfo& info);
// The words a setting accepts, for messages: "a, b or c".
std::string settingWords(const SettingInfo& info);

// How a member of type T is written to the settings JSON and read back. Specialised for the
// types settings hold; a flavour may add its own (say an error budget).
template <class T, class = void> struct SettingJson {}; // none: the JSON does not hold it

template <class T>
struct SettingJson<T, std::enable_if_t<std::is_arithmetic_v<T> && !std::is_same_v<T, bool>>> {
    // A float that is not finite (d_inf's "nothing seen") is null, and null reads as +inf.
    static nlohmann::json write(T v, const SettingInfo&) {
        if constexpr (std::is_floating_point_v<T>)
            if (!std::isfinite(v)) return nullptr;
        return v;
    }
    static T read(const nlohmann::json& j, const SettingInfo& info, const std::string& file,
                  const std::string& field) {
        if constexpr (std::is_floating_point_v<T>)
            if (j.is_null()) return std::numeric_limits<T>::infinity();
        if (!j.is_number() || (std::is_integral_v<T> && !j.is_number_integer()))
            throw Error(file, field,
                        std::is_integral_v<T> ? "expected an integer" : "expected a number");
        const double v = j.get<double>();
        if (!(v >= double(std::numeric_limits<T>::lowest()) &&
              v <= double(std::numeric_limits<T>::max())))
            throw Error(file, field, "out of range: " + j.dump());
        if (!(v >= info.lo && v <= info.hi))
            throw Error(file, field, "expected " + settingRange(info) + ", got " + j.dump());
        if constexpr (std::is_integral_v<T>)
            if (info.multipleOf > 1 && j.get<T>() % T(info.multipleOf) != 0)
                throw Error(file, field,
                            "expected a multiple of " + std::to_string(info.multipleOf));
        return j.get<T>();
    }
};

template <> struct SettingJson<bool> {
    static nlohmann::json write(bool v, const SettingInfo&) { return v; }
    static bool read(const nlohmann::json& j, const SettingInfo&, const std::string& file,
                     const std::string& field) {
        if (!j.is_boolean()) throw Error(file, field, "expected true or false");
        return j.get<bool>();
    }
};

template <> struct SettingJson<std::string> {
    static nlohmann::json write(const std::string& v, const SettingInfo&) { return v; }
    static std::string read(const nlohmann::json& j, const SettingInfo& info,
                            const std::string& file, const std::string& field);
};

template <class E> struct SettingJson<E, std::enable_if_t<std::is_enum_v<E>>> {
    static nlohmann::json write(E v, const SettingInfo& info) {
        return info.words.at(std::size_t(v));
    }
    static E read(const nlohmann::json& j, const SettingInfo& info, const std::string& file,
                  const std::string& field) {
        const std::string w = SettingJson<std::string>::read(j, info, file, field);
        for (std::size_t i = 0; i < info.words.size(); ++i)
            if (w == info.words[i]) return E(i);
        throw Error(file, field, "expected " + settingWords(info)); // unreachable: read checks
    }
};

template <class T> struct SettingJson<std::optional<T>> {
    static nlohmann::json write(const std::optional<T>& v, const SettingInfo& info) {
        return v ? SettingJson<T>::write(*v, info) : nlohmann::json(nullptr);
    }
    static std::optional<T> read(const nlohmann::json& j, const SettingInfo& info,
                                 const std::string& file, const std::string& field) {
        if (j.is_null()) return std::nullopt;
        return SettingJson<T>::read(j, info, file, field);
    }
};

template <> struct SettingJson<glm::vec3> {
    static nlohmann::json write(const glm::vec3& v, const SettingInfo&) { return {v.x, v.y, v.z}; }
    static glm::vec3 read(const nlohmann::json& j, const SettingInfo&, const std::string& file,
                          const std::string& field);
};

// A member type the JSON holds (a setting without a key may be of a type it does not).
template <class T>
concept JsonSetting = requires(const T& v, const SettingInfo& i) {
    SettingJson<T>::write(v, i);
};

template <class S> nlohmann::json settingsToJson(const S& s);
template <class S>
void settingsFromJson(const nlohmann::json& j, S& s, const std::string& file,
                      const std::string& prefix);

template <NestedSettings T> struct SettingJson<T> {
    static nlohmann::json write(const T& v, const SettingInfo&) { return settingsToJson(v); }
    static T read(const nlohmann::json& j, const SettingInfo&, const std::string& file,
                  const std::string& field) {
        if (!j.is_object()) throw Error(file, field, "expected an object");
        T v{};
        settingsFromJson(j, v, file, field + ".");
        return v;
    }
};

// Every setting of `s` that has a key, as one JSON object.
template <class S> nlohmann::json settingsToJson(const S& s) {
    nlohmann::json j = nlohmann::json::object();
    visitSettings(s, [&](const SettingInfo& info, const auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (JsonSetting<T>)
            if (info.key) j[info.key] = SettingJson<T>::write(v, info);
    });
    return j;
}

// Reads every setting of `s` that has a key from `j`; errors name `file` and the field as
// prefix + key ("settings.face_res").
template <class S>
void settingsFromJson(const nlohmann::json& j, S& s, const std::string& file,
                      const std::string& prefix) {
    visitSettings(s, [&](const SettingInfo& info, auto&& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (JsonSetting<T>) {
            if (!info.key) return;
            if (!j.is_object() || !j.contains(info.key)) {
                if (info.optional) return;
                throw Error(file, prefix + info.key, "missing from the shard list");
            }
            v = SettingJson<T>::read(j.at(info.key), info, file, prefix + info.key);
        }
    });
}

} // namespace specula
