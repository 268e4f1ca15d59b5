#include "probe_volume.h"

#include "components/reflection_probe/manifest_fields.h"
#include "engine/core/error.h"
#include "engine/core/glsl_host.h"

#include <algorithm>
#include <climits>
#include <cmath>

#include <nlohmann/json.hpp>

namespace specula {

namespace glsl {
#include "components/reflection_probe/shaders/probe_influence.glsl.h"
} // namespace glsl

using nlohmann::json;

namespace {

bool finite(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

glm::vec3 vec3Member(const json& obj, const char* key, const std::string& file,
                     const std::string& field) {
    const std::string where = field + "." + key;
    if (!obj.is_object() || !obj.contains(key)) throw Error(file, where, "missing");
    return probeVec3(obj[key], file, where);
}

float numberMember(const json& obj, const char* key, const std::string& file,
                   const std::string& field, float lo, float hi) {
    const std::string where = field + "." + key;
    const json& n = obj[key];
    if (!n.is_number() || !std::isfinite(n.get<double>()) || n.get<double>() < lo ||
        n.get<double>() > hi)
        throw Error(file, where,
                    "expected a number in [" + json(lo).dump() + ", " + json(hi).dump() +
                        "], got " + n.dump());
    return n.get<float>();
}

// A box whose every side is positive: zero-size and inverted boxes are refused here, not
// blended with.
Aabb boxMember(const json& obj, const std::string& file, const std::string& field,
               glm::vec3 offset) {
    if (!obj.is_object()) throw Error(file, field, "expected {\"min\": [..], \"max\": [..]}");
    const Aabb b{vec3Member(obj, "min", file, field) + offset,
                 vec3Member(obj, "max", file, field) + offset};
    if (!(b.min.x < b.max.x && b.min.y < b.max.y && b.min.z < b.max.z))
        throw Error(file, field,
                    "zero-size or inverted box: every component of min must lie below max");
    return b;
}

json boxJson(const Aabb& b) {
    return {{"min", {b.min.x, b.min.y, b.min.z}}, {"max", {b.max.x, b.max.y, b.max.z}}};
}

float volumeOf(const ProbeInfluence& i) {
    if (i.shape == ProbeInfluence::Shape::Sphere)
        return 4.f / 3.f * 3.14159265f * i.radius * i.radius * i.radius;
    const glm::vec3 e = i.box.extent();
    return e.x * e.y * e.z;
}

} // namespace

glm::vec3 probeVec3(const json& a, const std::string& file, const std::string& field) {
    if (!a.is_array() || a.size() != 3 || !a[0].is_number() || !a[1].is_number() ||
        !a[2].is_number())
        throw Error(file, field, "expected [x, y, z], got " + a.dump());
    const glm::vec3 v(a[0].get<float>(), a[1].get<float>(), a[2].get<float>());
    if (!finite(v) || glm::any(glm::greaterThan(glm::abs(v), glm::vec3(kMaxCoordinate))))
        throw Error(file, field, "expected finite coordinates within 1e7 m, got " + a.dump());
    return v;
}

int influenceShapeCode(const ProbeInfluence& i) {
    return i.shape == ProbeInfluence::Shape::Sphere ? glsl::kInfluenceSphere : glsl::kInfluenceBox;
}

float influenceDepth(const ProbeInfluence& i, glm::vec3 p) {
    return glsl::influenceDepthOf(influenceShapeCode(i), i.box.min, i.box.max, i.centre, i.radius,
                                  p);
}

float influenceWeight(const ProbeVolume& v, glm::vec3 p) {
    return glsl::influenceWeightOf(influenceDepth(v.influence, p), v.blendDistance);
}

bool blendsBefore(const ProbeVolume& a, const ProbeVolume& b) {
    if (a.priority != b.priority) return a.priority > b.priority;
    const float va = volumeOf(a.influence), vb = volumeOf(b.influence);
    if (va != vb) return va < vb;
    return a.name < b.name;
}

std::vector<std::size_t> influencingProbes(std::span<const ProbeVolume> probes, glm::vec3 p,
                                           int k) {
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < probes.size(); ++i)
        if (influenceWeight(probes[i], p) > 0.f) order.push_back(i);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return blendsBefore(probes[a], probes[b]);
    });
    if (order.size() > std::size_t(std::max(k, 0))) order.resize(std::size_t(std::max(k, 0)));
    return order;
}

ProbeBlend blendProbes(std::span<const ProbeVolume> probes, glm::vec3 p, int k) {
    ProbeBlend blend;
    for (std::size_t i : influencingProbes(probes, p, k)) {
        if (blend.sky <= 0.f) break;
        const float w = influenceWeight(probes[i], p) * blend.sky;
        blend.weights.emplace_back(i, w);
        blend.sky -= w;
    }
    blend.sky = std::max(0.f, blend.sky);
    return blend;
}

namespace {

// An int, never wrapped: 2^32 + 1 read as 1 would silently reorder a level's probes.
int priorityMember(const json& p, const std::string& file, const std::string& field) {
    const bool fits = p.is_number_unsigned()
                          ? p.get<std::uint64_t>() <= std::uint64_t(INT_MAX)
                          : p.is_number_integer() && p.get<std::int64_t>() >= INT_MIN &&
                                p.get<std::int64_t>() <= INT_MAX;
    if (!fits)
        throw Error(file, field + ".priority",
                    "expected an integer from " + std::to_string(INT_MIN) + " to " +
                        std::to_string(INT_MAX) + ", got " + p.dump());
    return p.get<int>();
}

} // namespace

json toJson(const ProbeVolume& v) {
    json influence;
    if (v.influence.shape == ProbeInfluence::Shape::Sphere)
        influence = {
            {"sphere",
             {{"centre", {v.influence.centre.x, v.influence.centre.y, v.influence.centre.z}},
              {"radius", v.influence.radius}}}};
    else
        influence = {{"box", boxJson(v.influence.box)}};
    return {{"name", v.name},
            {"position", {v.position.x, v.position.y, v.position.z}},
            {"proxy", boxJson(v.proxy)},
            {"influence", influence},
            {"blend_distance", v.blendDistance},
            {"priority", v.priority},
            {"cell_size", v.cellSize}};
}

ProbeVolume probeVolumeFromJson(const json& j, const std::string& file, const std::string& field) {
    if (!j.is_object()) throw Error(file, field, "expected an object");
    ProbeVolume v;
    if (!j.contains("name") || !j["name"].is_string() || j["name"].get<std::string>().empty())
        throw Error(file, field + ".name", "expected a non-empty string");
    v.name = j["name"].get<std::string>();
    v.position = vec3Member(j, "position", file, field);
    v.proxy = boxMember(j.value("proxy", json()), file, field + ".proxy", glm::vec3(0.f));
    const json& inf = j.value("influence", json());
    // One shape: a volume holding both would be read as whichever was tried first.
    if (inf.is_object() && inf.contains("sphere") && inf.contains("box"))
        throw Error(file, field + ".influence", "expected a box or a sphere, not both");
    if (inf.is_object() && inf.contains("sphere")) {
        v.influence.shape = ProbeInfluence::Shape::Sphere;
        v.influence.centre = vec3Member(inf["sphere"], "centre", file, field + ".influence.sphere");
        v.influence.radius =
            numberMember(inf["sphere"], "radius", file, field + ".influence.sphere", 1e-6f, 1e6f);
    } else {
        v.influence.box = boxMember(inf.is_object() ? inf.value("box", json()) : json(), file,
                                    field + ".influence.box", glm::vec3(0.f));
    }
    if (j.contains("blend_distance"))
        v.blendDistance = numberMember(j, "blend_distance", file, field, 0.f, 1e6f);
    if (j.contains("priority")) v.priority = priorityMember(j["priority"], file, field);
    if (j.contains("cell_size"))
        v.cellSize = numberMember(j, "cell_size", file, field, 1e-3f, 1e4f);
    return v;
}

void applyProbeMarkup(ProbeVolume& v, const json& o, const std::string& file,
                      const std::string& field) {
    if (!o.is_object()) return;
    if (o.contains("proxy")) v.proxy = boxMember(o["proxy"], file, field + ".proxy", v.position);
    if (o.contains("influence")) {
        const json& inf = o["influence"];
        const std::string where = field + ".influence";
        if (inf.is_object() && inf.contains("sphere") && !inf.contains("box")) {
            v.influence.shape = ProbeInfluence::Shape::Sphere;
            v.influence.centre = v.position;
            v.influence.radius =
                numberMember(inf["sphere"], "radius", file, where + ".sphere", 1e-6f, 1e6f);
        } else if (inf.is_object() && inf.contains("box") && !inf.contains("sphere")) {
            v.influence.shape = ProbeInfluence::Shape::Box;
            v.influence.box = boxMember(inf["box"], file, where + ".box", v.position);
        } else {
            throw Error(file, where,
                        "expected {\"box\": {\"min\": [..], \"max\": [..]}} or {\"sphere\": "
                        "{\"radius\": r}}, got " +
                            inf.dump());
        }
    }
    if (o.contains("blend_distance"))
        v.blendDistance = numberMember(o, "blend_distance", file, field, 0.f, 1e6f);
    if (o.contains("priority")) v.priority = priorityMember(o["priority"], file, field);
    if (o.contains("cell_size"))
        v.cellSize = numberMember(o, "cell_size", file, field, 1e-3f, 1e4f);
}

void validateProbeVolume(const ProbeVolume& v, const std::string& file, const std::string& field) {
    const auto proper = [](const Aabb& b) {
        return finite(b.min) && finite(b.max) && b.min.x < b.max.x && b.min.y < b.max.y &&
               b.min.z < b.max.z;
    };
    if (!finite(v.position)) throw Error(file, field + ".position", "not finite");
    if (!proper(v.proxy)) throw Error(file, field + ".proxy", "empty, zero-size or inverted box");
    if (v.influence.shape == ProbeInfluence::Shape::Box
            ? !proper(v.influence.box)
            : !(v.influence.radius > 0.f) || !finite(v.influence.centre))
        throw Error(file, field + ".influence", "empty, zero-size or inverted volume");
    if (!(v.blendDistance >= 0.f) || !std::isfinite(v.blendDistance))
        throw Error(file, field + ".blend_distance", "expected a finite number >= 0");
}

} // namespace specula
