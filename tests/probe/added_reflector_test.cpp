// Test mirrors dropped into a scene (specula-sandbox --add-reflector): the spec parser, the
// added mesh as Embree and the markup see it (mirror pixel counts against the closed-form
// projected areas), and the default camera placed in free space where it sees the reflector,
// on small glTF rooms written here (single-sided boxes, no camera node, no reflector).
#include "assetcooker/lib/scene/added_reflector.h"
#include "assetcooker/lib/scene/probe_setup.h"
#include "engine/core/error.h"
#include "engine/scene/components.h"
#include "support/scratch_dir_test.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include <glm/gtc/constants.hpp>

using namespace specula;
using nlohmann::json;

namespace {

// 36 vertices (non-indexed) of the unit cube centred at the origin, counter-clockwise seen
// from outside (outward) or from inside (inward: a room's walls).
std::vector<glm::vec3> unitCube(bool outward) {
    std::vector<glm::vec3> v;
    for (int axis = 0; axis < 3; ++axis)
        for (const float sign : {1.f, -1.f}) {
            const int u = (axis + 1) % 3, w = (axis + 2) % 3;
            std::array<glm::vec3, 4> c;
            const std::array<std::array<float, 2>, 4> uv{{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}};
            for (int i = 0; i < 4; ++i) {
                c[i][axis] = 0.5f * sign;
                c[i][u] = 0.5f * uv[i][0];
                c[i][w] = 0.5f * uv[i][1];
            }
            for (const std::array<int, 3> t : {std::array<int, 3>{0, 1, 2}, {0, 2, 3}}) {
                glm::vec3 a = c[t[0]], b = c[t[1]], d = c[t[2]];
                const bool out = glm::dot(glm::cross(b - a, d - a), a + b + d) > 0.f;
                if (out != outward) std::swap(b, d);
                v.insert(v.end(), {a, b, d});
            }
        }
    return v;
}

// A glTF scene of boxes: solid ones (faces outward) and rooms (faces inward), each a node
// with a translation and a scale, sharing two meshes; a diffuse material; no camera node.
struct BoxScene {
    json nodes = json::array();

    void box(const std::string& name, glm::vec3 centre, glm::vec3 size, bool room) {
        nodes.push_back({{"name", name},
                         {"mesh", room ? 1 : 0},
                         {"translation", {centre.x, centre.y, centre.z}},
                         {"scale", {size.x, size.y, size.z}}});
    }

    std::string write(const std::filesystem::path& dir) const {
        std::vector<glm::vec3> positions = unitCube(true);
        const std::vector<glm::vec3> inward = unitCube(false);
        positions.insert(positions.end(), inward.begin(), inward.end());
        const std::size_t bytes = positions.size() * sizeof(glm::vec3);
        std::ofstream(dir / "boxes.bin", std::ios::binary)
            .write(reinterpret_cast<const char*>(positions.data()), std::streamsize(bytes));
        json roots = json::array();
        for (std::size_t i = 0; i < nodes.size(); ++i)
            roots.push_back(i);
        auto accessor = [](std::size_t offset) {
            return json{{"bufferView", 0},       {"byteOffset", offset},
                        {"componentType", 5126}, {"count", 36},
                        {"type", "VEC3"},        {"min", {-0.5, -0.5, -0.5}},
                        {"max", {0.5, 0.5, 0.5}}};
        };
        auto mesh = [](int accessor) {
            return json{
                {"primitives", {{{"attributes", {{"POSITION", accessor}}}, {"material", 0}}}}};
        };
        const json j = {
            {"asset", {{"version", "2.0"}}},
            {"scene", 0},
            {"scenes", {{{"nodes", roots}}}},
            {"nodes", nodes},
            {"meshes", {mesh(0), mesh(1)}},
            {"materials",
             {{{"name", "plaster"},
               {"pbrMetallicRoughness",
                {{"baseColorFactor", {0.7, 0.7, 0.7, 1.0}},
                 {"metallicFactor", 0.0},
                 {"roughnessFactor", 1.0}}}}}},
            {"buffers", {{{"uri", "boxes.bin"}, {"byteLength", bytes}}}},
            {"bufferViews", {{{"buffer", 0}, {"byteLength", bytes}}}},
            {"accessors", {accessor(0), accessor(36 * sizeof(glm::vec3))}},
        };
        const std::filesystem::path path = dir / "boxes.gltf";
        std::ofstream(path) << j.dump();
        return path.string();
    }
};

std::size_t mirrorPixels(ProbeScene& scene, const CameraView& cam) {
    const GroundTruthImage gt = traceGroundTruth(scene, cam, true);
    std::size_t n = 0;
    for (float v : gt.mirrorMask.pixels)
        n += v > 0.5f ? 1 : 0;
    return n;
}

// The message of the UsageError parseAddedReflector throws for `spec` (empty: none thrown).
std::string parseError(const std::string& spec) {
    try {
        parseAddedReflector(spec);
    } catch (const UsageError& e) {
        EXPECT_EQ(e.field(), "--add-reflector") << spec;
        return e.what();
    }
    return {};
}

class AddedReflectorScene : public test::ScratchDirTest {
protected:
    AddedReflectorScene() : ScratchDirTest("specula-added-reflector") {}

    // A 6 x 3 x 6 m closed room on the floor y = 0 (faces inward), nothing else.
    std::string room(bool enclosure = false) {
        BoxScene s;
        s.box("room", {0.f, 1.5f, 0.f}, {6.f, 3.f, 6.f}, true);
        // A closed crate around (0, 1.2, 0), from outside a solid.
        if (enclosure) s.box("crate", {0.f, 1.2f, 0.f}, {1.2f, 1.2f, 1.2f}, false);
        return s.write(root_);
    }
};

} // namespace

TEST(AddedReflectorSpec, ParsesSpheresAndBoxes) {
    const AddedReflector s = parseAddedReflector("sphere:0,1.2,-0.5,0.3");
    EXPECT_EQ(s.shape, AddedReflector::Shape::Sphere);
    EXPECT_EQ(s.centre, glm::vec3(0.f, 1.2f, -0.5f));
    EXPECT_FLOAT_EQ(s.radius, 0.3f);
    EXPECT_EQ(describeAddedReflector(s), "sphere:0,1.2,-0.5,0.3");

    const AddedReflector b = parseAddedReflector("box:1,0.5,-1,0.4,1e0,.25");
    EXPECT_EQ(b.shape, AddedReflector::Shape::Box);
    EXPECT_EQ(b.centre, glm::vec3(1.f, 0.5f, -1.f));
    EXPECT_EQ(b.size, glm::vec3(0.4f, 1.f, 0.25f));
    EXPECT_EQ(describeAddedReflector(b), "box:1,0.5,-1,0.4,1,0.25");
}

TEST(AddedReflectorSpec, RejectsBadSpecsNamingTheFlagAndTheFault) {
    const std::vector<std::pair<std::string, std::string>> cases{
        {"", "no shape"},
        {"0,1,0,1", "no shape"},
        {"cone:0,1,0,1", "unknown shape 'cone'"},
        {"Sphere:0,1,0,1", "unknown shape"},
        {"sphere", "no numbers"},
        {"sphere:", "sphere takes 4 numbers"},
        {"sphere:0,1,0", "got 3"},
        {"sphere:0,1,0,1,2", "got 5"},
        {"box:0,1,0,1,1", "box takes 6 numbers"},
        {"box:0,1,0,1", "got 4"},
        {"sphere:0,1,,1", "'' is not a number"},
        {"sphere:a,1,0,1", "'a' is not a number"},
        {"sphere:0,1,0,1m", "'1m' is not a number"},
        {"sphere:0, 1,0,1", "' 1' is not a number"},
        {"sphere:nan,1,0,1", "'nan' is not a finite number"},
        {"sphere:0,inf,0,1", "'inf' is not a finite number"},
        {"sphere:0,1,1e400,1", "'1e400' is not a finite number"},
        {"sphere:0,1,2e6,1", "'2e6' is not a finite number"},
        {"sphere:0,1,0,0", "the radius must be > 0, got 0"},
        {"sphere:0,1,0,-0.5", "the radius must be > 0, got -0.5"},
        {"box:0,1,0,1,0,1", "the box sizes must be > 0"},
        {"box:0,1,0,1,1,-2", "the box sizes must be > 0"},
    };
    for (const auto& [spec, fault] : cases) {
        const std::string message = parseError(spec);
        ASSERT_FALSE(message.empty()) << "'" << spec << "' was accepted";
        EXPECT_EQ(message.rfind("--add-reflector: ", 0), 0u) << message;
        EXPECT_NE(message.find(fault), std::string::npos) << message;
        // Says what the flag takes.
        EXPECT_NE(message.find("sphere:x,y,z,r or box:x,y,z,sx,sy,sz"), std::string::npos)
            << message;
    }
}

// An added sphere joins the markup as a perfect mirror node like a glTF reflector: named,
// a root of the scene, moved by ReflectorRoots, and as many mirror pixels in the traced
// ground truth as the closed-form disc it projects to.
TEST_F(AddedReflectorScene, SphereIsAMirrorNodeOfTheClosedFormArea) {
    ProbeScene scene(room(), "");
    ASSERT_TRUE(scene.markup.reflectors.empty());
    const ecs::Entity e = addReflector(scene, parseAddedReflector("sphere:0,1.2,0,0.3"));

    ASSERT_EQ(scene.markup.reflectors.size(), 1u);
    EXPECT_EQ(scene.markup.reflectors[0].node, "added_reflector_0");
    EXPECT_EQ(scene.markup.reflectors[0].f0, -1.f);
    ASSERT_EQ(scene.markup.reflectors[0].meshes, std::vector<ecs::Entity>{e});
    EXPECT_EQ(scene.markup.mirrorEntities.count(e), 1u);
    EXPECT_EQ(scene.loaded.roots.back(), e);
    EXPECT_EQ(scene.registry.get<Name>(e).value, "added_reflector_0");
    const Mesh& mesh = scene.registry.get<Mesh>(e);
    ASSERT_EQ(mesh.primitives.size(), 1u);
    EXPECT_EQ(mesh.primitives[0].material->metallicFactor, 1.f);
    EXPECT_EQ(mesh.primitives[0].material->roughnessFactor, 0.f);
    EXPECT_EQ(mesh.primitives[0].mesh->indices.size() / 3, std::size_t(2 * 48 * (24 - 1)));
    // The probe centre is the reflector's (the room has no probe node).
    const glm::vec3 centre = markupProbeCentre(scene.registry, scene.markup, scene.loaded);
    EXPECT_NEAR(glm::length(centre - glm::vec3(0.f, 1.2f, 0.f)), 0.f, 1e-5f);

    // Seen head-on from 2 m: a disc of angular radius asin(r / D), tan of it over
    // tan(fov / 2) of half the image height. The 48 x 24 facets shrink the silhouette by
    // under 0.3% of the radius, the pixel grid blurs its rim by about a pixel: 2% tolerance.
    const int w = 320, h = 240;
    const float fov = glm::radians(50.f), r = 0.3f, d = 2.f;
    const CameraView cam =
        CameraView::lookAt({0.f, 1.2f, d}, {0.f, 1.2f, 0.f}, {0.f, 1.f, 0.f}, fov, w, h);
    const double rho = std::tan(std::asin(r / d)) / std::tan(fov / 2) * (h / 2.0);
    const double disc = glm::pi<double>() * rho * rho; // about 4790 pixels
    EXPECT_NEAR(double(mirrorPixels(scene, cam)), disc, 0.02 * disc);

    // A second one gets the next name; the walk's roots move both like any reflector node.
    addReflector(scene, parseAddedReflector("box:1.5,0.5,-1,0.4,1,0.4"));
    EXPECT_EQ(scene.markup.reflectors.back().node, "added_reflector_1");
    ReflectorRoots roots(scene);
    ASSERT_EQ(roots.roots().size(), 2u);
    EXPECT_EQ(roots.roots()[0].first, e);
    EXPECT_EQ(roots.roots()[0].second, glm::vec3(0.f, 1.2f, 0.f));
    roots.setOffset(scene.registry, {0.1f, 0.f, 0.f});
    EXPECT_NEAR(scene.registry.get<Transform>(e).world[3].x, 0.1f, 1e-6f);
    EXPECT_NEAR(scene.registry.get<Transform>(roots.roots()[1].first).world[3].x, 1.6f, 1e-6f);
}

// A box seen head-on along its axis shows its front face alone: a rectangle of its edge
// lengths over the front face's distance.
TEST_F(AddedReflectorScene, BoxShowsItsFrontFaceRectangle) {
    ProbeScene scene(room(), "", {parseAddedReflector("box:0,1.2,0,0.6,0.4,0.5")});
    ASSERT_EQ(scene.markup.reflectors.size(), 1u);
    EXPECT_EQ(scene.registry.get<Mesh>(scene.markup.reflectors[0].meshes[0])
                  .primitives[0]
                  .mesh->positions.size(),
              24u);
    const int w = 320, h = 240;
    const float fov = glm::radians(50.f), d = 2.f;
    const CameraView cam =
        CameraView::lookAt({0.f, 1.2f, d}, {0.f, 1.2f, 0.f}, {0.f, 1.f, 0.f}, fov, w, h);
    const double f = (h / 2.0) / std::tan(fov / 2), front = d - 0.25;
    const double halfW = 0.3 / front * f, halfH = 0.2 / front * f; // 44.1 and 29.4 pixels
    const double rect = 4.0 * halfW * halfH;                       // about 5190 pixels
    // Centred on the image's middle (a pixel corner), the rectangle holds the centres of
    // 2 round(halfW) x 2 round(halfH) pixels: 88 x 58 = 5104, 1.6% under its area.
    const double lattice = 4.0 * std::floor(halfW + 0.5) * std::floor(halfH + 0.5);
    const double seen = double(mirrorPixels(scene, cam));
    EXPECT_NEAR(seen, rect, 0.02 * rect);
    EXPECT_NEAR(seen, lattice, 0.002 * lattice);
}

// With no camera node, the old default (3.5 m from +Z) stands behind the 6 m room's wall;
// the default camera is found inside the room instead, looking at the reflector.
TEST_F(AddedReflectorScene, DefaultCameraStandsInsideAClosedRoomAndSeesTheReflector) {
    ProbeScene scene(room(), "", {parseAddedReflector("sphere:0,1.2,0,0.3")});
    const CameraView cam = sceneCameraView(scene, 64, 48);
    const glm::vec3 eye = cam.eye();
    EXPECT_TRUE(eye.x > -3.f && eye.x < 3.f && eye.y > 0.f && eye.y < 3.f && eye.z > -3.f &&
                eye.z < 3.f)
        << eye.x << "," << eye.y << "," << eye.z;
    const std::size_t seen = mirrorPixels(scene, cam);
    EXPECT_GE(double(seen), DefaultViewpointRules::kMinMirrorShare * 64 * 48) << seen;

    // The walk's orbit is that camera's: same eye at t = 0, same distance and height.
    const CameraOrbit o = sceneCameraOrbit(scene);
    const glm::vec3 centre = markupProbeCentre(scene.registry, scene.markup, scene.loaded);
    EXPECT_NEAR(o.height, eye.y - centre.y, 1e-4f);
    EXPECT_NEAR(glm::length(walkOrbitCameraView(scene, 64, 48, 0.f).eye() - eye), 0.f, 1e-4f);
    // Deterministic: a second scene gets the same camera.
    ProbeScene again(room(), "", {parseAddedReflector("sphere:0,1.2,0,0.3")});
    EXPECT_EQ(sceneCameraView(again, 64, 48).view, cam.view);
}

// In free space the default camera is the old one: from +Z, 3.5 m away and 0.6 m up.
TEST_F(AddedReflectorScene, DefaultCameraInOpenSpaceIsTheOldDefault) {
    BoxScene s;
    s.box("ground", {0.f, -0.05f, 0.f}, {40.f, 0.1f, 40.f}, false);
    ProbeScene scene(s.write(root_), "", {parseAddedReflector("sphere:1,1.2,-2,0.3")});
    const glm::vec3 eye = sceneCameraView(scene, 64, 48).eye();
    EXPECT_NEAR(glm::length(eye - glm::vec3(1.f, 1.8f, 1.5f)), 0.f, 1e-4f)
        << eye.x << "," << eye.y << "," << eye.z;
}

// A reflector shut in a closed crate is seen from nowhere: the error says so and how to
// give a viewpoint.
TEST_F(AddedReflectorScene, EnclosedReflectorHasNoFreeViewpoint) {
    const std::string path = room(true);
    ProbeScene scene(path, "", {parseAddedReflector("sphere:0,1.2,0,0.3")});
    for (int attempt = 0; attempt < 2; ++attempt) { // the failed search is kept, not redone
        try {
            sceneCameraView(scene, 64, 48);
            FAIL() << "a camera was found";
        } catch (const Error& e) {
            const std::string m = e.what();
            EXPECT_EQ(e.file(), path);
            EXPECT_NE(m.find("no free viewpoint"), std::string::npos) << m;
            EXPECT_NE(m.find("camera node"), std::string::npos) << m;
            EXPECT_NE(m.find("--add-reflector"), std::string::npos) << m;
        }
    }
    // Added outside the crate, a second reflector gives the camera something to see.
    addReflector(scene, parseAddedReflector("sphere:1.8,1.2,0,0.3"));
    EXPECT_NO_THROW(sceneCameraView(scene, 64, 48));
}

// A scene's camera node wins over the search: the bundled scenes keep their views.
TEST(AddedReflectorCamera, BundledScenesKeepTheirCameraNode) {
    for (const char* rel : {"assets/room/room.gltf", "assets/bowl_room/bowl_room.gltf",
                            "assets/truck_room/truck_room.gltf", "assets/sky_only/sky_only.gltf"}) {
        ProbeScene scene(std::string(SPECULA_SOURCE_DIR) + "/" + rel, "");
        glm::mat4 world(0.f);
        for (ecs::Entity e : scene.loaded.entities)
            if (scene.registry.has<Camera>(e)) {
                world = scene.registry.get<Transform>(e).world;
                break;
            }
        ASSERT_NE(world, glm::mat4(0.f)) << rel << " has no camera node";
        EXPECT_EQ(sceneCameraView(scene, 64, 48).view, glm::inverse(world)) << rel;
        // An added reflector does not move it either.
        addReflector(scene, parseAddedReflector("sphere:0.5,1,0.5,0.1"));
        EXPECT_EQ(sceneCameraView(scene, 64, 48).view, glm::inverse(world)) << rel;
    }
}
