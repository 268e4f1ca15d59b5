#include "added_reflector.h"

#include "assetcooker/lib/scene/probe_setup.h"
#include "engine/core/error.h"
#include "engine/scene/components.h"
#include "engine/scene/transform_system.h"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <memory>
#include <sstream>
#include <vector>

#include <glm/gtc/constants.hpp>

namespace specula {

namespace {

constexpr float kMaxMagnitude = 1e6f;
constexpr int kSphereSegments = 48, kSphereRings = 24;

[[noreturn]] void fail(const std::string& spec, const std::string& what) {
    throw UsageError(kAddReflectorFlag, what + " in '" + spec + "' (expected " +
                                            kAddReflectorForms + ", e.g. sphere:0,1.2,0,0.3)");
}

std::vector<std::string> splitCommas(const std::string& text) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = text.find(',', start);
        parts.push_back(text.substr(start, comma - start));
        if (comma == std::string::npos) return parts;
        start = comma + 1;
    }
}

float parseNumber(const std::string& spec, const std::string& text) {
    // from_chars takes no leading '+' or spaces: neither does the flag.
    double v = 0.0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, v);
    if (text.empty() || ec == std::errc::invalid_argument || ptr != end)
        fail(spec, "'" + text + "' is not a number");
    if (ec == std::errc::result_out_of_range || !std::isfinite(v) ||
        std::abs(v) > double(kMaxMagnitude))
        fail(spec, "'" + text + "' is not a finite number up to 1e6");
    return float(v);
}

std::string formatNumber(float v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

// Makes every triangle counter-clockwise seen from outside (the face normal points away from
// the local origin, the shape's centre) and drops degenerate ones (a UV sphere's poles).
void addOutwardTriangle(MeshData& md, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const glm::vec3 pa = md.positions[a], pb = md.positions[b], pc = md.positions[c];
    const glm::vec3 n = glm::cross(pb - pa, pc - pa);
    if (!(glm::dot(n, n) > 1e-12f * glm::dot(pb - pa, pb - pa) * glm::dot(pc - pa, pc - pa)))
        return;
    if (glm::dot(n, pa + pb + pc) < 0.f) std::swap(b, c);
    md.indices.insert(md.indices.end(), {a, b, c});
}

std::shared_ptr<MeshData> sphereMesh(float radius) {
    auto md = std::make_shared<MeshData>();
    for (int i = 0; i <= kSphereRings; ++i) {
        const float theta = glm::pi<float>() * float(i) / float(kSphereRings);
        // The poles exactly on the axis, so their triangles are exactly degenerate.
        const bool pole = i == 0 || i == kSphereRings;
        const float sinTheta = pole ? 0.f : std::sin(theta);
        const float cosTheta = pole ? (i == 0 ? 1.f : -1.f) : std::cos(theta);
        for (int j = 0; j <= kSphereSegments; ++j) {
            const float phi = glm::two_pi<float>() * float(j) / float(kSphereSegments);
            const glm::vec3 n(sinTheta * std::sin(phi), cosTheta, sinTheta * std::cos(phi));
            md->positions.push_back(radius * n);
            md->normals.push_back(n);
            md->uvs.emplace_back(float(j) / float(kSphereSegments), float(i) / float(kSphereRings));
        }
    }
    const auto at = [](int i, int j) { return std::uint32_t(i * (kSphereSegments + 1) + j); };
    for (int i = 0; i < kSphereRings; ++i)
        for (int j = 0; j < kSphereSegments; ++j) {
            addOutwardTriangle(*md, at(i, j), at(i + 1, j), at(i + 1, j + 1));
            addOutwardTriangle(*md, at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
    md->boundsMin = glm::vec3(-radius);
    md->boundsMax = glm::vec3(radius);
    return md;
}

std::shared_ptr<MeshData> boxMesh(glm::vec3 size) {
    auto md = std::make_shared<MeshData>();
    const glm::vec3 h = 0.5f * size;
    for (int axis = 0; axis < 3; ++axis)
        for (const float sign : {1.f, -1.f}) {
            glm::vec3 n(0.f);
            n[axis] = sign;
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            const auto base = std::uint32_t(md->positions.size());
            for (const auto [su, sv] : std::array<std::array<float, 2>, 4>{
                     {{-1.f, -1.f}, {1.f, -1.f}, {1.f, 1.f}, {-1.f, 1.f}}}) {
                glm::vec3 p(0.f);
                p[axis] = sign * h[axis];
                p[u] = su * h[u];
                p[v] = sv * h[v];
                md->positions.push_back(p);
                md->normals.push_back(n);
                md->uvs.emplace_back(0.5f * (su + 1.f), 0.5f * (sv + 1.f));
            }
            addOutwardTriangle(*md, base, base + 1, base + 2);
            addOutwardTriangle(*md, base, base + 2, base + 3);
        }
    md->boundsMin = -h;
    md->boundsMax = h;
    return md;
}

bool nameTaken(const ProbeScene& scene, const std::string& name) {
    for (ecs::Entity e : scene.loaded.entities)
        if (const Name* n = scene.registry.find<Name>(e); n && n->value == name) return true;
    return false;
}

} // namespace

AddedReflector parseAddedReflector(const std::string& spec) {
    const std::size_t colon = spec.find(':');
    const std::string shape = spec.substr(0, colon);
    AddedReflector r;
    std::size_t expected = 0;
    if (shape == "sphere") {
        r.shape = AddedReflector::Shape::Sphere;
        expected = 4;
    } else if (shape == "box") {
        r.shape = AddedReflector::Shape::Box;
        expected = 6;
    } else {
        fail(spec, colon == std::string::npos ? "no shape"
                                              : "unknown shape '" + shape + "' (sphere or box)");
    }
    if (colon == std::string::npos) fail(spec, "no numbers after '" + shape + "'");
    const std::vector<std::string> parts = splitCommas(spec.substr(colon + 1));
    if (parts.size() != expected)
        fail(spec, shape + " takes " + std::to_string(expected) + " numbers (" +
                       (expected == 4 ? "x,y,z,r" : "x,y,z,sx,sy,sz") + "), got " +
                       std::to_string(parts.size()));
    std::vector<float> v;
    for (const std::string& p : parts)
        v.push_back(parseNumber(spec, p));
    r.centre = glm::vec3(v[0], v[1], v[2]);
    if (r.shape == AddedReflector::Shape::Sphere) {
        r.radius = v[3];
        if (!(r.radius > 0.f)) fail(spec, "the radius must be > 0, got " + formatNumber(r.radius));
    } else {
        r.size = glm::vec3(v[3], v[4], v[5]);
        if (!(r.size.x > 0.f && r.size.y > 0.f && r.size.z > 0.f))
            fail(spec, "the box sizes must be > 0, got " + formatNumber(r.size.x) + "," +
                           formatNumber(r.size.y) + "," + formatNumber(r.size.z));
    }
    return r;
}

std::string describeAddedReflector(const AddedReflector& r) {
    std::string s = r.shape == AddedReflector::Shape::Sphere ? "sphere:" : "box:";
    s += formatNumber(r.centre.x) + "," + formatNumber(r.centre.y) + "," +
         formatNumber(r.centre.z) + ",";
    if (r.shape == AddedReflector::Shape::Sphere) return s + formatNumber(r.radius);
    return s + formatNumber(r.size.x) + "," + formatNumber(r.size.y) + "," + formatNumber(r.size.z);
}

ecs::Entity addReflector(ProbeScene& scene, const AddedReflector& r) {
    std::string name;
    for (int i = 0;; ++i) {
        name = "added_reflector_" + std::to_string(i);
        if (!nameTaken(scene, name)) break;
    }
    auto material = std::make_shared<MaterialData>();
    material->baseColorFactor = glm::vec4(1.f);
    material->metallicFactor = 1.f;
    material->roughnessFactor = 0.f;
    material->name = name;

    Mesh mesh;
    mesh.name = name;
    mesh.primitives.push_back(
        Primitive{r.shape == AddedReflector::Shape::Sphere ? sphereMesh(r.radius) : boxMesh(r.size),
                  material});

    ecs::Registry& reg = scene.registry;
    const ecs::Entity e = reg.create();
    reg.emplace<Name>(e, Name{name});
    Transform t;
    t.translation = r.centre;
    reg.emplace<Transform>(e, t);
    const MeshData& md = *mesh.primitives.front().mesh;
    const glm::vec3 lo = r.centre + md.boundsMin, hi = r.centre + md.boundsMax;
    reg.emplace<Mesh>(e, std::move(mesh));

    scene.loaded.entities.push_back(e);
    scene.loaded.roots.push_back(e);
    scene.loaded.boundsMin = glm::min(scene.loaded.boundsMin, lo);
    scene.loaded.boundsMax = glm::max(scene.loaded.boundsMax, hi);
    scene.markup.reflectors.push_back(ReflectorMarkup{name, {e}, -1.f, 0.f, nullptr});
    scene.markup.mirrorEntities.insert(e);
    scene.defaultView.forget();
    updateWorldTransforms(reg);
    return e;
}

} // namespace specula
