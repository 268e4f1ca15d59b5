#include "assetcooker/lib/level/level_probes.h"

#include "assetcooker/lib/scene/probe_sanity.h"
#include "components/reflection_probe/manifest_fields.h"
#include "engine/core/error.h"
#include "engine/core/glsl_host.h"
#include "engine/raytrace/embree_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <span>
#include <sstream>
#include <tuple>

namespace specula {
namespace glsl {
#include "components/reflection_probe/distance/shaders/distance_level_params.glsl.h"
} // namespace glsl

using nlohmann::json;

namespace {

// ProbeVolume::priority is an int.
constexpr std::int64_t kMaxPriority = std::numeric_limits<int>::max();

// A probe being gathered, with the markup objects to apply onto it in order (later wins).
struct PendingProbe {
    ProbeVolume volume;
    std::vector<std::tuple<json, std::string, std::string>> members; // (members, file, field)
};

// The members of a volume (probe_volume.h), as the markup and a probe list write them.
constexpr std::array<const char*, 5> kVolumeMembers{"proxy", "influence", "blend_distance",
                                                    "priority", "cell_size"};
// What the effect plan reads from a probe node's markup besides (effect_plan.h, plan_budget.h).
constexpr std::array<const char*, 6> kPlanMembers{"max_error", "max_error_deg", "motion_range",
                                                  "flavour",   "fresnel",       "background"};

// Throws Error naming `file` and `field`.KEY for a key of `o` not in `known`: a misspelt
// member ("blend_distanse") would otherwise be ignored without a word.
void refuseUnknownKeys(const json& o, std::span<const char* const> known, const std::string& file,
                       const std::string& field) {
    if (!o.is_object()) return;
    for (const auto& [key, value] : o.items())
        if (std::ranges::none_of(known, [&](const char* k) { return key == k; })) {
            std::string expected;
            for (const char* k : known)
                expected += (expected.empty() ? "" : ", ") + std::string(k);
            throw Error(file, field + "." + key,
                        "unknown member (expected one of " + expected + ")");
        }
}

// The members of one probe's markup or list entry checked before they are applied: no
// unknown key at any depth, and a priority that fits the runtime's int (a larger one would
// wrap around).
void checkProbeMembers(const json& o, bool planMembers, const std::string& file,
                       const std::string& field) {
    std::vector<const char*> known(kVolumeMembers.begin(), kVolumeMembers.end());
    if (planMembers) known.insert(known.end(), kPlanMembers.begin(), kPlanMembers.end());
    refuseUnknownKeys(o, known, file, field);
    static constexpr std::array<const char*, 2> kBox{"min", "max"};
    static constexpr std::array<const char*, 2> kShapes{"box", "sphere"};
    static constexpr std::array<const char*, 1> kSphere{"radius"};
    if (o.contains("proxy")) refuseUnknownKeys(o["proxy"], kBox, file, field + ".proxy");
    if (o.contains("influence") && o["influence"].is_object()) {
        const json& inf = o["influence"];
        refuseUnknownKeys(inf, kShapes, file, field + ".influence");
        if (inf.contains("box"))
            refuseUnknownKeys(inf["box"], kBox, file, field + ".influence.box");
        if (inf.contains("sphere"))
            refuseUnknownKeys(inf["sphere"], kSphere, file, field + ".influence.sphere");
    }
    if (o.contains("priority") && o["priority"].is_number_integer()) {
        const json& p = o["priority"];
        const bool fits = p.is_number_unsigned()
                              ? p.get<std::uint64_t>() <= std::uint64_t(kMaxPriority)
                              : p.get<std::int64_t>() >= -std::int64_t(kMaxPriority) - 1 &&
                                    p.get<std::int64_t>() <= std::int64_t(kMaxPriority);
        if (!fits)
            throw Error(file, field + ".priority",
                        "expected an integer in " +
                            std::to_string(-std::int64_t(kMaxPriority) - 1) + " .. " +
                            std::to_string(kMaxPriority) + ", got " + p.dump());
    }
}

// The probe list file's entries merged into `probes` (see LevelProbeSources::file).
void mergeProbeList(std::vector<PendingProbe>& probes, const std::string& file) {
    const json doc = parseManifestJson(readManifestText(file), file);
    const json& list = doc.is_object() && doc.contains("probes") ? doc["probes"] : doc;
    if (!list.is_array()) throw Error(file, "probes", "expected an array of probes");
    std::map<std::string, std::string> listed; // name -> the entry that gave it
    for (std::size_t i = 0; i < list.size(); ++i) {
        const json& p = list[i];
        const std::string field = "probes[" + std::to_string(i) + "]";
        if (!p.is_object()) throw Error(file, field, "expected an object");
        std::string name = "probe_list_" + std::to_string(i);
        if (p.contains("name")) {
            if (!p["name"].is_string() || p["name"].get<std::string>().empty())
                throw Error(file, field + ".name", "expected a non-empty string");
            name = p["name"].get<std::string>();
        }
        // Two entries of one name would be one probe, the first one's members overridden.
        if (const auto [at, added] = listed.emplace(name, field); !added)
            throw Error(file, field + ".name",
                        "\"" + name + "\" is also the name of " + at->second +
                            ": every probe of a list needs its own name");
        json members = p;
        members.erase("name");
        members.erase("position");
        checkProbeMembers(members, false, file, field);
        PendingProbe* target = nullptr;
        for (PendingProbe& q : probes)
            if (q.volume.name == name) target = &q;
        if (!target) {
            if (!p.contains("position"))
                throw Error(file, field + ".position", "missing (a new probe needs a position)");
            probes.push_back({});
            target = &probes.back();
            target->volume.name = name;
        }
        if (p.contains("position"))
            target->volume.position = probeVec3(p["position"], file, field + ".position");
        target->members.emplace_back(std::move(members), file, field);
    }
}

// The default proxy: the room the probe stands in, measured so that furniture does not shrink
// it. Each side of the box reaches as far as the axis ray from the probe (the scene's bound
// where it escapes), and farther when a 16 x 16 grid of rays over that face of the cube about
// the probe sees a farther plane across the axis on which a good share of them end (at least
// 4 rays, and a quarter of the most any such plane holds, within 5 cm): the side lies on the
// median of those hits, a planar wall's own coordinate, so an empty box room gets its box
// exactly. Why: the axis ray alone stops at the first table or cupboard in its way, while the
// wall behind still fills a good part of the view; a high percentile of all the hits would run
// out through any doorway or window filling a tenth of the face; and the axis ray keeps a long
// hall past its pillars and arches one room (a row of probes along it shares its influences
// out only within one proxy). Only hits on surfaces facing along the axis count (a floor or
// side wall met at a slant is no wall of this side) and, in a second round, only those inside
// the first round's box on the other two axes (a wall seen through a window or past a jamb
// lies outside it; that first box takes an axis ray only where it finds no plane, for axis
// rays run out through windows).
Aabb measuredProxy(const EmbreeScene& env, const Aabb& sceneBounds, glm::vec3 p) {
    if (sceneBounds.empty()) return Aabb::cube(p, 0.75f);
    constexpr int kGrid = 16;
    constexpr float kPlane = 0.05f; // metres: hits this close along the axis are one plane
    struct Ray {
        float along;  // the hit's coordinate along the side's axis, times the side's sign
        bool across;  // on a surface facing along the axis
        glm::vec3 at; // the hit point
    };
    std::array<std::vector<Ray>, 6> rays; // per side: -x, +x, -y, +y, -z, +z; the axis ray first
    for (int side = 0; side < 6; ++side) {
        const int axis = side / 2;
        const float sign = side % 2 ? 1.f : -1.f;
        for (int i = -1; i < kGrid * kGrid; ++i) {
            glm::vec3 dir(0.f);
            dir[axis] = sign;
            if (i >= 0) {
                dir[(axis + 1) % 3] = (2.f * float(i % kGrid) + 1.f) / kGrid - 1.f;
                dir[(axis + 2) % 3] = (2.f * float(i / kGrid) + 1.f) / kGrid - 1.f;
            }
            const float bound = sign > 0 ? sceneBounds.max[axis] : sceneBounds.min[axis];
            if (const std::optional<Hit> hit = env.intersect(p, dir))
                rays[side].push_back({sign * p[axis] + hit->t,
                                      std::abs(hit->geometricNormal[axis]) > 0.7f, hit->position});
            else
                rays[side].push_back({sign * bound, false, p});
        }
    }
    Aabb box = sceneBounds;
    for (int round = 0; round < 2; ++round) {
        Aabb measured;
        for (int side = 0; side < 6; ++side) {
            const int axis = side / 2;
            const float sign = side % 2 ? 1.f : -1.f;
            std::vector<float> walls;
            for (const Ray& r : std::span(rays[side]).subspan(1)) {
                bool wall = r.across;
                for (int k = 1; k < 3; ++k) {
                    const int o = (axis + k) % 3;
                    wall = wall && r.at[o] >= box.min[o] - kPlane && r.at[o] <= box.max[o] + kPlane;
                }
                if (wall) walls.push_back(r.along);
            }
            std::sort(walls.begin(), walls.end(), std::greater<float>());
            std::vector<std::size_t> plane(walls.size()); // hits within kPlane nearer, from each
            for (std::size_t i = 0, j = 0; i < walls.size(); plane[i] = j - i, ++i)
                while (j < walls.size() && walls[j] >= walls[i] - kPlane)
                    ++j;
            const std::size_t most = plane.empty() ? 0 : *std::ranges::max_element(plane);
            const std::size_t need = std::max<std::size_t>(4, (most + 3) / 4);
            const auto found =
                std::ranges::find_if(plane, [&](std::size_t n) { return n >= need; });
            const float axisRay = rays[side][0].along;
            float along = axisRay;
            if (found != plane.end()) {
                const std::size_t i = std::size_t(found - plane.begin());
                along = walls[i + plane[i] / 2]; // the median of the plane's hits
                if (round == 1) along = std::max(along, axisRay);
            }
            const float bound = sign > 0 ? sceneBounds.max[axis] : sceneBounds.min[axis];
            const float reach = std::clamp(along - sign * p[axis], 0.01f, // never a flat box
                                           std::max(0.01f, sign * (bound - p[axis])));
            (sign > 0 ? measured.max : measured.min)[axis] = p[axis] + sign * reach;
        }
        box = measured;
    }
    return box;
}

std::string pointText(glm::vec3 p) {
    std::ostringstream s;
    s << '(' << p.x << ", " << p.y << ", " << p.z << ')';
    return s.str();
}

} // namespace

GatheredProbes gatherLevelProbes(ProbeScene& scene, const LevelProbeSources& sources) {
    const std::string& file = scene.path;
    std::vector<PendingProbe> pending;
    for (const ProbeMarkup& m : scene.markup.probes) {
        PendingProbe p;
        p.volume.name = m.node;
        p.volume.position = m.position;
        const std::string field = "nodes[" + m.node + "].extras.specula_probe";
        checkProbeMembers(m.options, true, file, field);
        p.members.emplace_back(m.options, file, field);
        pending.push_back(std::move(p));
    }
    for (std::size_t i = 0; i < sources.positions.size(); ++i) {
        if (i >= pending.size()) {
            pending.push_back({});
            pending.back().volume.name = "probe_" + std::to_string(i);
        }
        pending[i].volume.position = sources.positions[i];
    }
    if (!sources.file.empty()) mergeProbeList(pending, sources.file);
    // The runtime draws a level's probes from one uniform block: a larger level would bake
    // for nothing, then be refused by every view that loads it.
    if (pending.size() > std::size_t(glsl::kMaxLevelProbes))
        throw Error(sources.file.empty() ? file : sources.file, "probes",
                    "the level has " + std::to_string(pending.size()) +
                        " probes; the runtime draws at most " +
                        std::to_string(glsl::kMaxLevelProbes) + " in one view: split the level");
    if (pending.empty()) {
        pending.push_back({});
        pending.back().volume.name = "probe";
        pending.back().volume.position =
            markupProbeCentre(scene.registry, scene.markup, scene.loaded);
    }

    const EmbreeScene env(scene.registry,
                          [&](ecs::Entity e) { return scene.markup.mirrorEntities.count(e) == 0; });
    const Aabb sceneBounds{scene.loaded.boundsMin, scene.loaded.boundsMax};
    GatheredProbes out;
    std::vector<bool> influenceDefaulted;
    for (PendingProbe& p : pending) {
        ProbeVolume& v = p.volume;
        v.proxy = Aabb{};
        v.influence.box = Aabb{};
        std::string proxyFile = file, proxyField = "probe " + v.name + ".proxy";
        for (const auto& [members, from, field] : p.members) {
            applyProbeMarkup(v, members, from, field);
            if (members.is_object() && members.contains("proxy"))
                proxyFile = from, proxyField = field + ".proxy";
        }
        // The lookup projects from the probe's position onto its proxy: from outside, a
        // direction meets the box behind the probe or not at all.
        if (!v.proxy.empty() && !v.proxy.contains(v.position))
            throw Error(proxyFile, proxyField,
                        "probe " + v.name + " at " + pointText(v.position) +
                            " lies outside its proxy box " + pointText(v.proxy.min) + " .. " +
                            pointText(v.proxy.max));
        if (v.proxy.empty()) v.proxy = measuredProxy(env, sceneBounds, v.position);
        influenceDefaulted.push_back(v.influence.shape == ProbeInfluence::Shape::Box &&
                                     v.influence.box.empty());
        // A defaulted influence is the proxy grown by one blend distance: the weight is 1
        // throughout the room the probe owns and fades outside it. Fading inside would hand
        // the sky a share of every reflector near a wall, floor or table top of a closed room.
        if (influenceDefaulted.back())
            v.influence.box = Aabb{v.proxy.min - glm::vec3(v.blendDistance),
                                   v.proxy.max + glm::vec3(v.blendDistance)};
    }
    // Probes in one room (a row along a hall) would share one proxy and so one influence:
    // a defaulted influence is cut half-way to every other probe inside its proxy, on the
    // axis that separates them most, reaching one blend distance past the half-way point:
    // neighbours overlap by twice the blend distance, so wherever one fades out the other
    // still weighs 1 and no sky shows between them (engine-style blending leaves to the sky
    // what the probes' weights do not cover).
    for (std::size_t i = 0; i < pending.size(); ++i) {
        if (!influenceDefaulted[i]) continue;
        ProbeVolume& v = pending[i].volume;
        for (std::size_t j = 0; j < pending.size(); ++j) {
            const glm::vec3 d = pending[j].volume.position - v.position;
            if (j == i || !v.proxy.contains(pending[j].volume.position)) continue;
            const glm::vec3 a = glm::abs(d);
            const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
            if (a[axis] <= 0.f) continue;
            const float mid = v.position[axis] + 0.5f * d[axis];
            if (d[axis] > 0.f)
                v.influence.box.max[axis] =
                    std::min(v.influence.box.max[axis], mid + v.blendDistance);
            else
                v.influence.box.min[axis] =
                    std::max(v.influence.box.min[axis], mid - v.blendDistance);
        }
    }
    for (PendingProbe& p : pending) {
        ProbeVolume& v = p.volume;
        validateProbeVolume(v, file, "probe " + v.name);
        // The bake's own placement measurement (probe_sanity.h), at a coarser sampling: the
        // bake itself refuses such a probe later, this names it before any work.
        const ProbePlacement placed =
            measureProbePlacement(scene.registry, scene.markup, v.position, 256);
        if (placed.hits > 0 && 2 * placed.backHits > placed.hits)
            out.warnings.push_back("probe " + v.name + " lies inside solid geometry (" +
                                   std::to_string(placed.backHits) + " of " +
                                   std::to_string(placed.hits) +
                                   " rays from it meet the back of a surface first)");
        for (const ProbeVolume& q : out.probes) {
            if (q.name == v.name) throw Error(file, "probe " + v.name, "two probes have this name");
            if (q.priority == v.priority && q.proxy == v.proxy && q.influence == v.influence)
                out.warnings.push_back("probes " + q.name + " and " + v.name +
                                       " have equal priority and identical volumes: " +
                                       std::min(q.name, v.name) + " is blended first (by name)");
        }
        out.probes.push_back(v);
    }
    return out;
}

} // namespace specula
