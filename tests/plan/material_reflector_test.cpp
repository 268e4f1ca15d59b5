// Reflectors found from the glTF materials (metallic and smooth), not only from the markup:
// small glTF files written here, loaded by the real loader, read by readSceneMarkup.
#include "assetcooker/lib/scene/scene_markup.h"
#include "components/reflection_probe/system/reflector_roughness.h"
#include "engine/core/error.h"
#include "engine/scene/components.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/transform_system.h"
#include "support/scratch_dir_test.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <fstream>
#include <map>
#include <optional>
#include <set>

using namespace specula;
using nlohmann::json;

namespace {

// A glTF scene of one-triangle meshes, one mesh per node, sharing one buffer.
struct GltfScene {
    json images = json::array();   // {"uri": file} beside scene.gltf
    json textures = json::array(); // {"source": image}
    json materials = json::array();
    json meshes = json::array();
    json nodes = json::array();
    std::vector<int> roots;

    // `pbr`: the pbrMetallicRoughness object; nullopt leaves the block out.
    int material(const std::string& name, std::optional<json> pbr) {
        json m = {{"name", name}};
        if (pbr) m["pbrMetallicRoughness"] = *pbr;
        materials.push_back(m);
        return int(materials.size()) - 1;
    }
    int metal(const std::string& name, double metallic, double roughness,
              std::vector<double> colour = {1, 1, 1, 1}) {
        return material(name, json{{"baseColorFactor", colour},
                                   {"metallicFactor", metallic},
                                   {"roughnessFactor", roughness}});
    }
    // A node with a mesh of `material` (-1: no mesh); a root unless `parent` is given.
    int node(const std::string& name, int material, const json& extras = nullptr, int parent = -1) {
        json n = {{"name", name}, {"translation", {double(nodes.size()) * 2.0, 0.0, 0.0}}};
        if (material >= 0) {
            meshes.push_back(
                {{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"material", material}}}}});
            n["mesh"] = int(meshes.size()) - 1;
        }
        if (!extras.is_null()) n["extras"] = extras;
        nodes.push_back(n);
        const int i = int(nodes.size()) - 1;
        if (parent >= 0)
            nodes[std::size_t(parent)]["children"].push_back(i);
        else
            roots.push_back(i);
        return i;
    }
    std::filesystem::path write(const std::filesystem::path& dir) const {
        const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
        std::ofstream(dir / "scene.bin", std::ios::binary)
            .write(reinterpret_cast<const char*>(triangle), sizeof(triangle));
        const json j = {
            {"asset", {{"version", "2.0"}}},
            {"scene", 0},
            {"scenes", {{{"nodes", roots}}}},
            {"nodes", nodes},
            {"meshes", meshes},
            {"materials", materials},
            {"buffers", {{{"uri", "scene.bin"}, {"byteLength", sizeof(triangle)}}}},
            {"bufferViews", {{{"buffer", 0}, {"byteLength", sizeof(triangle)}}}},
            {"accessors",
             {{{"bufferView", 0},
               {"componentType", 5126},
               {"count", 3},
               {"type", "VEC3"},
               {"min", {0, 0, 0}},
               {"max", {1, 1, 0}}}}},
        };
        json full = j;
        if (!images.empty()) full["images"] = images, full["textures"] = textures;
        const std::filesystem::path path = dir / "scene.gltf";
        std::ofstream(path) << full.dump();
        return path;
    }
};

class MaterialReflector : public test::ScratchDirTest {
protected:
    MaterialReflector() : ScratchDirTest("specula-material-reflector") {}

    SceneMarkup read(const GltfScene& g, const ReflectorRule& rule = {}) {
        const std::filesystem::path path = g.write(root_);
        scene_ = loadGltf(path.string(), reg_);
        updateWorldTransforms(reg_);
        return readSceneMarkup(reg_, scene_, path.string(), rule);
    }
    // Reflector node name -> its f0.
    static std::map<std::string, float> reflectors(const SceneMarkup& m) {
        std::map<std::string, float> out;
        for (const ReflectorMarkup& r : m.reflectors)
            out[r.node] = r.f0;
        return out;
    }
    static bool inEnvironment(const SceneMarkup& m, const std::string& object) {
        for (const EnvironmentObject& o : m.objects)
            if (o.name == object) return true;
        return false;
    }

    ecs::Registry reg_;
    LoadedScene scene_;
};

} // namespace

TEST_F(MaterialReflector, LoaderKeepsTheFactorsWithGltfDefaults) {
    GltfScene g;
    g.node("chrome", g.metal("chrome", 0.25, 0.75));
    g.node("plain", g.material("plain", std::nullopt));
    g.node("partial", g.material("partial", json{{"metallicFactor", 0.5}}));
    read(g);
    std::map<std::string, const MaterialData*> byName;
    reg_.view<Mesh>().each([&](ecs::Entity, Mesh& m) {
        const MaterialData* md = m.primitives.at(0).material.get();
        byName[md->name] = md;
    });
    ASSERT_EQ(byName.size(), 3u);
    EXPECT_FLOAT_EQ(byName["chrome"]->metallicFactor, 0.25f);
    EXPECT_FLOAT_EQ(byName["chrome"]->roughnessFactor, 0.75f);
    EXPECT_FLOAT_EQ(byName["plain"]->metallicFactor, 1.f);
    EXPECT_FLOAT_EQ(byName["plain"]->roughnessFactor, 1.f);
    EXPECT_FLOAT_EQ(byName["partial"]->metallicFactor, 0.5f);
    EXPECT_FLOAT_EQ(byName["partial"]->roughnessFactor, 1.f);
}

TEST_F(MaterialReflector, SmoothMetalIsAReflectorWithItsBaseColourLuminance) {
    GltfScene g;
    g.node("mirror", g.metal("silver", 1.0, 0.0, {0.9, 0.8, 0.5, 1.0}));
    g.node("wall", g.metal("paint", 0.0, 0.9));
    const SceneMarkup m = read(g);
    const auto r = reflectors(m);
    ASSERT_EQ(r.size(), 1u);
    ASSERT_EQ(r.count("mirror"), 1u);
    EXPECT_NEAR(r.at("mirror"), 0.2126f * 0.9f + 0.7152f * 0.8f + 0.0722f * 0.5f, 1e-5f);
    EXPECT_EQ(m.reflectors[0].meshes.size(), 1u);
    EXPECT_EQ(m.mirrorEntities.size(), 1u);
    EXPECT_TRUE(inEnvironment(m, "wall"));
    EXPECT_FALSE(inEnvironment(m, "mirror"));
}

TEST_F(MaterialReflector, BrightBaseColourClampsF0ToOne) {
    GltfScene g;
    g.node("mirror", g.metal("chrome", 1.0, 0.0, {1, 1, 1, 1}));
    const auto r = reflectors(read(g));
    ASSERT_EQ(r.count("mirror"), 1u);
    EXPECT_FLOAT_EQ(r.at("mirror"), 1.f);
}

TEST_F(MaterialReflector, MarkupFalseExcludesAQualifyingSubtree) {
    GltfScene g;
    const int chrome = g.metal("chrome", 1.0, 0.0);
    g.node("kept", chrome);
    g.node("not_me", chrome, json{{"specula_reflector", false}});
    const int group = g.node("group", -1, json{{"specula_reflector", false}});
    g.node("child", chrome, nullptr, group);
    const SceneMarkup m = read(g);
    const auto r = reflectors(m);
    ASSERT_EQ(r.size(), 1u);
    EXPECT_EQ(r.count("kept"), 1u);
    // The excluded ones are environment.
    EXPECT_TRUE(inEnvironment(m, "not_me"));
    EXPECT_TRUE(inEnvironment(m, "group"));
}

TEST_F(MaterialReflector, MarkupTrueOnARoughNodeStillMakesAReflector) {
    GltfScene g;
    g.node("marked", g.metal("paint", 0.0, 1.0), json{{"specula_reflector", true}});
    g.node("glass", g.metal("paint2", 0.0, 1.0), json{{"specula_reflector", {{"f0", 0.04}}}});
    const auto r = reflectors(read(g));
    ASSERT_EQ(r.size(), 2u);
    EXPECT_LT(r.at("marked"), 0.f); // a perfect mirror, as before
    EXPECT_FLOAT_EQ(r.at("glass"), 0.04f);
}

TEST_F(MaterialReflector, MarkupWinsOverTheMaterialsOfItsSubtree) {
    GltfScene g;
    const int chrome = g.metal("chrome", 1.0, 0.0, {0.5, 0.5, 0.5, 1.0});
    const int parent = g.node("parent", chrome, json{{"specula_reflector", {{"f0", 0.2}}}});
    g.node("child", chrome, nullptr, parent);
    const SceneMarkup m = read(g);
    ASSERT_EQ(m.reflectors.size(), 1u); // one per marked node, not one more per material
    EXPECT_EQ(m.reflectors[0].node, "parent");
    EXPECT_FLOAT_EQ(m.reflectors[0].f0, 0.2f);
    EXPECT_EQ(m.reflectors[0].meshes.size(), 2u);
}

TEST_F(MaterialReflector, RoughnessComesFromTheMaterialOrTheMarkup) {
    GltfScene g;
    g.node("polished", g.metal("polished", 1.0, 0.08));
    g.node("brushed", g.metal("brushed", 1.0, 0.6),
           json{{"specula_reflector", {{"roughness", 0.35}}}});
    g.node("mirror", g.metal("mirror", 1.0, 0.0));
    const SceneMarkup m = read(g);
    std::map<std::string, float> roughness;
    for (const ReflectorMarkup& r : m.reflectors)
        roughness[r.node] = r.roughness;
    ASSERT_EQ(roughness.size(), 3u);
    EXPECT_FLOAT_EQ(roughness.at("polished"), 0.08f); // the material's factor
    EXPECT_FLOAT_EQ(roughness.at("brushed"), 0.35f);  // the markup wins
    EXPECT_FLOAT_EQ(roughness.at("mirror"), 0.f);
    // Out of [0, 1] is an error naming the node's member.
    GltfScene bad;
    bad.node("bad", bad.metal("x", 1.0, 0.0), json{{"specula_reflector", {{"roughness", 1.5}}}});
    try {
        read(bad);
        FAIL() << "roughness 1.5 was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("specula_reflector.roughness"), std::string::npos)
            << e.what();
    }
}

TEST_F(MaterialReflector, ThresholdsComeFromTheRule) {
    GltfScene g;
    g.node("almost_metal", g.metal("a", 0.89, 0.0));
    g.node("almost_smooth", g.metal("b", 1.0, 0.11));
    g.node("edge", g.metal("c", 0.9, 0.1));
    const auto strict = reflectors(read(g));
    ASSERT_EQ(strict.size(), 1u);
    EXPECT_EQ(strict.count("edge"), 1u);

    ecs::Registry reg;
    const std::filesystem::path path = g.write(root_);
    const LoadedScene scene = loadGltf(path.string(), reg);
    updateWorldTransforms(reg);
    const SceneMarkup loose =
        readSceneMarkup(reg, scene, path.string(), ReflectorRule{0.85f, 0.15f});
    EXPECT_EQ(reflectors(loose).size(), 3u);
}

TEST_F(MaterialReflector, NoPbrBlockMeansRoughMetalNotAMirror) {
    GltfScene g;
    g.node("default_pbr", g.material("bare", std::nullopt));
    const SceneMarkup m = read(g);
    EXPECT_TRUE(m.reflectors.empty());
    EXPECT_TRUE(inEnvironment(m, "default_pbr"));
}

TEST_F(MaterialReflector, MarkupOfTheWrongTypeIsStillRefused) {
    GltfScene g;
    g.node("odd", g.metal("chrome", 1.0, 0.0), json{{"specula_reflector", "yes"}});
    EXPECT_THROW(read(g), Error);
}

TEST_F(MaterialReflector, OutOfRangeFactorsAreClampedAndSaid) {
    GltfScene g;
    g.node("over", g.metal("over", 1.5, -0.5));
    const SceneMarkup m = read(g);
    const MaterialData& md = *reg_.get<Mesh>(scene_.entities.at(0)).primitives.at(0).material;
    EXPECT_FLOAT_EQ(md.metallicFactor, 1.f);
    EXPECT_FLOAT_EQ(md.roughnessFactor, 0.f);
    EXPECT_EQ(scene_.warnings.size(), 2u);
    EXPECT_EQ(m.reflectors.size(), 1u);
}

// An 8-bit RGB PNG of w x h texels, row by row.
void writePng(const std::filesystem::path& file, int w, int h,
              const std::vector<std::uint8_t>& rgb) {
    auto out = OIIO::ImageOutput::create(file.string());
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open(file.string(), OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::UINT8)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, rgb.data()));
    out->close();
}

// glTF's metallic-roughness texture multiplies the factors: roughness in G, metalness in B,
// stored linearly (not sRGB). A rough factor over a smooth texture is a smooth metal.
// The rule reads the texture's means (is the mesh smooth metal?); the reflector it makes
// reads the texture texel by texel: its factor, and the texture as its roughness map.
TEST_F(MaterialReflector, TheMetallicRoughnessTextureQualifiesByItsMeansAndIsKeptAsAMap) {
    // Two texels: G codes 10 and 31 (linear mean 20.5/255 = 0.0804, under the rule's 0.1;
    // decoded as sRGB the mean would be 0.0075), B 255 and 229 (metalness 0.949).
    writePng(root_ / "mr.png", 2, 1, {0, 10, 255, 0, 31, 229});
    GltfScene g;
    g.images.push_back({{"uri", "mr.png"}});
    g.textures.push_back({{"source", 0}});
    g.node("textured", g.material("textured", json{{"metallicFactor", 1.0},
                                                   {"roughnessFactor", 1.0},
                                                   {"metallicRoughnessTexture", {{"index", 0}}}}));
    g.node("half", g.material("half", json{{"metallicFactor", 1.0},
                                           {"roughnessFactor", 0.5},
                                           {"metallicRoughnessTexture", {{"index", 0}}}}));
    g.node("untextured", g.metal("untextured", 1.0, 1.0));
    const SceneMarkup m = read(g);
    const MaterialData& md = *reg_.get<Mesh>(scene_.entities.at(0)).primitives.at(0).material;
    EXPECT_NEAR(md.roughnessTextureMean, 20.5f / 255.f, 1e-6f);
    EXPECT_NEAR(md.metallicTextureMean, 242.f / 255.f, 1e-6f);
    EXPECT_FLOAT_EQ(md.roughnessFactor, 1.f); // the factor as stated
    EXPECT_NEAR(md.roughnessTextureMin, 10.f / 255.f, 1e-6f);
    std::map<std::string, const ReflectorMarkup*> byNode;
    for (const ReflectorMarkup& r : m.reflectors)
        byNode[r.node] = &r;
    ASSERT_EQ(byNode.size(), 2u) << "the untextured rough metal is no reflector";
    EXPECT_FLOAT_EQ(byNode.at("textured")->roughness, 1.f);
    EXPECT_FLOAT_EQ(byNode.at("half")->roughness, 0.5f);
    for (const char* node : {"textured", "half"}) {
        ASSERT_TRUE(byNode.at(node)->roughnessMap) << node;
        EXPECT_EQ(byNode.at(node)->roughnessMap.get(), md.metallicRoughnessTexture.get());
    }
    // Texel by texel: the first texel's centre reads G = 10, the second's 31.
    const Image* map = byNode.at("half")->roughnessMap.get();
    EXPECT_NEAR(roughnessAt(0.5f, map, {0.25f, 0.5f}), 0.5f * 10.f / 255.f, 1e-6f);
    EXPECT_NEAR(roughnessAt(0.5f, map, {0.75f, 0.5f}), 0.5f * 31.f / 255.f, 1e-6f);
}

// "roughness" is a number in [0, 1] or "material"; "material" takes the node's material,
// and over a subtree of two materials their mean roughness, uniform (one map cannot stand
// for both).
TEST_F(MaterialReflector, MarkupRoughnessMaterialTakesTheMaterials) {
    GltfScene bad;
    bad.node("bad", bad.metal("x", 0.0, 0.2),
             json{{"specula_reflector", {{"roughness", "shiny"}}}});
    try {
        read(bad);
        FAIL() << "\"shiny\" was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("specula_reflector.roughness"), std::string::npos)
            << e.what();
    }
    reg_ = ecs::Registry();
    GltfScene g;
    const int pair = g.node("pair", -1, json{{"specula_reflector", {{"roughness", "material"}}}});
    g.node("a", g.metal("a", 0.0, 0.2), nullptr, pair);
    g.node("b", g.metal("b", 0.0, 0.6), nullptr, pair);
    g.node("one", g.metal("c", 0.0, 0.3), json{{"specula_reflector", {{"roughness", "material"}}}});
    const SceneMarkup m = read(g);
    std::map<std::string, const ReflectorMarkup*> byNode;
    for (const ReflectorMarkup& r : m.reflectors)
        byNode[r.node] = &r;
    ASSERT_EQ(byNode.size(), 2u);
    EXPECT_NEAR(byNode.at("pair")->roughness, 0.4f, 1e-6f);
    EXPECT_FALSE(byNode.at("pair")->roughnessMap);
    EXPECT_FLOAT_EQ(byNode.at("one")->roughness, 0.3f);
    EXPECT_FALSE(byNode.at("one")->roughnessMap);
}

TEST_F(MaterialReflector, AnUnreadableMetallicRoughnessTextureIsAnErrorNamingTheField) {
    std::ofstream(root_ / "broken.png") << "not a png";
    GltfScene g;
    g.images.push_back({{"uri", "broken.png"}});
    g.textures.push_back({{"source", 0}});
    g.node("textured", g.material("textured", json{{"metallicRoughnessTexture", {{"index", 0}}}}));
    try {
        read(g);
        FAIL() << "an undecodable texture was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("images[0]"), std::string::npos) << e.what();
    }
}

// The bundled scenes: their materials are all rough dielectrics, so the reflectors are
// exactly the nodes their markup names, as before materials counted.
TEST(MaterialReflectorBundled, BundledScenesKeepTheirMarkedReflectors) {
    for (const char* name : {"room", "truck_room", "bowl_room", "sky_only"}) {
        const std::filesystem::path path = std::filesystem::path(SPECULA_SOURCE_DIR) / "assets" /
                                           name / (std::string(name) + ".gltf");
        std::set<std::string> marked;
        const json j = json::parse(std::ifstream(path));
        for (const json& n : j["nodes"])
            if (n.contains("extras") && n["extras"].contains("specula_reflector") &&
                n["extras"]["specula_reflector"] != false)
                marked.insert(n.value("name", ""));
        ecs::Registry reg;
        const LoadedScene scene = loadGltf(path.string(), reg);
        updateWorldTransforms(reg);
        const SceneMarkup m = readSceneMarkup(reg, scene, path.string());
        std::set<std::string> found;
        for (const ReflectorMarkup& r : m.reflectors)
            found.insert(r.node);
        EXPECT_FALSE(marked.empty()) << name;
        EXPECT_EQ(found, marked) << name;
        EXPECT_EQ(m.reflectors.size(), marked.size()) << name;
    }
}
