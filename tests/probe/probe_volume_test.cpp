// A probe's volumes (probe_volume.h) against closed-form geometry: the depth inside a box
// or sphere, the weight's ramp over the blend distance, engine-style blending (priority,
// then the smaller volume, then the name), the markup's probe-relative members and their
// errors, and the level index's JSON form.
#include "components/reflection_probe/probe_volume.h"
#include "engine/core/error.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace specula {
namespace {

using nlohmann::json;

ProbeVolume boxProbe(const std::string& name, glm::vec3 lo, glm::vec3 hi, float blend = 0.5f,
                     int priority = 0) {
    ProbeVolume v;
    v.name = name;
    v.position = 0.5f * (lo + hi);
    v.proxy = {lo, hi};
    v.influence.box = {lo, hi};
    v.blendDistance = blend;
    v.priority = priority;
    return v;
}

TEST(ProbeVolume, DepthIsTheDistanceToTheNearestBoundary) {
    ProbeInfluence box;
    box.box = {glm::vec3(-2, 0, -1), glm::vec3(2, 3, 1)};
    EXPECT_FLOAT_EQ(influenceDepth(box, glm::vec3(0, 1.5f, 0)), 1.f);       // z faces 1 m away
    EXPECT_FLOAT_EQ(influenceDepth(box, glm::vec3(1.75f, 1.5f, 0)), 0.25f); // +x face
    EXPECT_FLOAT_EQ(influenceDepth(box, glm::vec3(2.5f, 1.5f, 0)), -0.5f);  // outside
    ProbeInfluence sphere;
    sphere.shape = ProbeInfluence::Shape::Sphere;
    sphere.centre = glm::vec3(1, 1, 1);
    sphere.radius = 2.f;
    EXPECT_FLOAT_EQ(influenceDepth(sphere, glm::vec3(1, 1, 2.5f)), 0.5f);
    EXPECT_FLOAT_EQ(influenceDepth(sphere, glm::vec3(4, 1, 1)), -1.f);
}

TEST(ProbeVolume, WeightRampsLinearlyOverTheBlendDistance) {
    const ProbeVolume v = boxProbe("a", glm::vec3(-2), glm::vec3(2), 0.5f);
    for (float inside : {0.f, 0.1f, 0.25f, 0.4f, 0.5f, 1.f, 2.f})
        EXPECT_NEAR(influenceWeight(v, glm::vec3(2.f - inside, 0, 0)), std::min(1.f, inside / 0.5f),
                    1e-6f)
            << inside;
    EXPECT_EQ(influenceWeight(v, glm::vec3(2.01f, 0, 0)), 0.f);
    ProbeVolume hard = v;
    hard.blendDistance = 0.f;
    EXPECT_EQ(influenceWeight(hard, glm::vec3(1.999f, 0, 0)), 1.f);
    EXPECT_EQ(influenceWeight(hard, glm::vec3(2.001f, 0, 0)), 0.f);
}

TEST(ProbeVolume, BlendTakesPriorityThenTheSmallerVolumeAndLeavesTheRestToTheSky) {
    // A large room probe and a small one inside it; the point lies 0.25 m inside the small
    // one's boundary (its weight 0.5) and deep inside the large one.
    const std::vector<ProbeVolume> probes{
        boxProbe("room", glm::vec3(-5), glm::vec3(5)),
        boxProbe("alcove", glm::vec3(-1), glm::vec3(1)),
    };
    const glm::vec3 p(0.75f, 0, 0);
    const ProbeBlend b = blendProbes(probes, p, 4);
    ASSERT_EQ(b.weights.size(), 2u);
    EXPECT_EQ(b.weights[0].first, 1u); // the smaller volume first
    EXPECT_NEAR(b.weights[0].second, 0.5f, 1e-6f);
    EXPECT_NEAR(b.weights[1].second, 0.5f, 1e-6f); // the room takes what is left
    EXPECT_NEAR(b.sky, 0.f, 1e-6f);

    // A higher priority wins over the smaller volume.
    std::vector<ProbeVolume> prioritised = probes;
    prioritised[0].priority = 1;
    const ProbeBlend bp = blendProbes(prioritised, p, 4);
    EXPECT_EQ(bp.weights[0].first, 0u);
    EXPECT_NEAR(bp.weights[0].second, 1.f, 1e-6f);
    EXPECT_EQ(bp.weights.size(), 1u);

    // K = 1 keeps one probe; the rest is the sky's.
    const ProbeBlend one = blendProbes(probes, p, 1);
    ASSERT_EQ(one.weights.size(), 1u);
    EXPECT_NEAR(one.sky, 0.5f, 1e-6f);
    // Outside every volume: all sky.
    EXPECT_TRUE(blendProbes(probes, glm::vec3(9, 0, 0), 4).weights.empty());
}

TEST(ProbeVolume, IdenticalProbesBlendInNameOrderWhateverTheirOrder) {
    const ProbeVolume b = boxProbe("b", glm::vec3(-1), glm::vec3(1));
    const ProbeVolume a = boxProbe("a", glm::vec3(-1), glm::vec3(1));
    const std::vector<ProbeVolume> ab{a, b}, ba{b, a};
    const auto first = [](const std::vector<ProbeVolume>& probes) {
        return probes[blendProbes(probes, glm::vec3(0), 1).weights.at(0).first].name;
    };
    EXPECT_EQ(first(ab), "a");
    EXPECT_EQ(first(ba), "a");
}

TEST(ProbeVolume, MarkupBoxesAreRelativeToTheProbe) {
    ProbeVolume v;
    v.name = "p";
    v.position = glm::vec3(10, 1, -3);
    applyProbeMarkup(v, json::parse(R"({"proxy": {"min": [-1, -1, -2], "max": [1, 2, 2]},
                                     "influence": {"sphere": {"radius": 4}},
                                     "blend_distance": 0.25, "priority": 3, "cell_size": 2})"),
                     "s.gltf", "nodes[p].extras.specula_probe");
    EXPECT_EQ(v.proxy.min, glm::vec3(9, 0, -5));
    EXPECT_EQ(v.proxy.max, glm::vec3(11, 3, -1));
    EXPECT_EQ(v.influence.shape, ProbeInfluence::Shape::Sphere);
    EXPECT_EQ(v.influence.centre, v.position);
    EXPECT_EQ(v.influence.radius, 4.f);
    EXPECT_EQ(v.blendDistance, 0.25f);
    EXPECT_EQ(v.priority, 3);
    EXPECT_EQ(v.cellSize, 2.f);
    validateProbeVolume(v, "s.gltf", "p");

    // The level index's form reads back to the same volume.
    EXPECT_EQ(probeVolumeFromJson(toJson(v), "level.json", "probes[0]"), ProbeVolume(v));
}

TEST(ProbeVolume, ZeroSizeOrInvertedVolumesAreErrorsNamingTheField) {
    const auto errorOf = [](const char* text) -> std::string {
        ProbeVolume v;
        try {
            applyProbeMarkup(v, json::parse(text), "s.gltf", "nodes[p].extras.specula_probe");
        } catch (const Error& e) {
            return e.what();
        }
        return "";
    };
    EXPECT_NE(errorOf(R"({"influence": {"box": {"min": [0, 0, 0], "max": [1, 0, 1]}}})")
                  .find("s.gltf: nodes[p].extras.specula_probe.influence.box: zero-size"),
              std::string::npos);
    EXPECT_NE(errorOf(R"({"proxy": {"min": [1, 0, 0], "max": [0, 1, 1]}})")
                  .find("specula_probe.proxy: zero-size or inverted"),
              std::string::npos);
    EXPECT_NE(errorOf(R"({"influence": {"sphere": {"radius": 0}}})")
                  .find("specula_probe.influence.sphere.radius"),
              std::string::npos);
    EXPECT_NE(errorOf(R"({"blend_distance": -1})").find("specula_probe.blend_distance"),
              std::string::npos);
    EXPECT_NE(errorOf(R"({"priority": 0.5})").find("specula_probe.priority"), std::string::npos);
    EXPECT_NE(errorOf(R"({"influence": {"cone": {}}})").find("specula_probe.influence"),
              std::string::npos);
    EXPECT_EQ(errorOf(R"({"influence": {"box": {"min": [0, 0, 0], "max": [1, 1, 1]}}})"), "");
}

// A level.json influence holding a box and a sphere used to be read as the sphere; both readers
// (the level's and the markup's) now refuse it naming the field.
TEST(ProbeVolume, AnInfluenceWithBothShapesIsAnError) {
    ProbeVolume v;
    v.name = "p";
    v.proxy = v.influence.box = Aabb{glm::vec3(-1.f), glm::vec3(1.f)};
    json level = toJson(v);
    level["influence"]["sphere"] = {{"centre", {0, 0, 0}}, {"radius", 1}};
    ASSERT_TRUE(level["influence"].contains("box"));
    try {
        probeVolumeFromJson(level, "level.json", "probes[0]");
        ADD_FAILURE() << "an influence with a box and a sphere was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("level.json: probes[0].influence: expected a box or "
                                             "a sphere, not both"),
                  std::string::npos)
            << e.what();
    }
    level["influence"].erase("box");
    EXPECT_EQ(probeVolumeFromJson(level, "level.json", "probes[0]").influence.shape,
              ProbeInfluence::Shape::Sphere);
    ProbeVolume markup = v;
    EXPECT_THROW(applyProbeMarkup(markup,
                                  json::parse(R"({"influence": {"box": {"min": [0, 0, 0], "max": )"
                                              R"([1, 1, 1]}, "sphere": {"radius": 1}}})"),
                                  "s.gltf", "p"),
                 Error);
}

// A hand-edited level.json's priority past an int (issue 34) used to wrap (2^32 + 1 read as 1,
// silently reordering the blend); both readers refuse it naming the field, and keep the ends.
TEST(ProbeVolume, APriorityPastAnIntIsAnErrorNotAWrap) {
    ProbeVolume v;
    v.name = "p";
    v.proxy = v.influence.box = Aabb{glm::vec3(-1.f), glm::vec3(1.f)};
    for (const json& priority : {json(4294967297ull), json(-2147483649ll), json(2147483648ull)}) {
        json level = toJson(v);
        level["priority"] = priority;
        try {
            probeVolumeFromJson(level, "level.json", "probes[0]");
            ADD_FAILURE() << priority.dump() << " was read";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("level.json: probes[0].priority: expected an "
                                                 "integer from -2147483648 to 2147483647"),
                      std::string::npos)
                << e.what();
        }
        ProbeVolume markup = v;
        EXPECT_THROW(applyProbeMarkup(markup, json{{"priority", priority}}, "s.gltf", "p"), Error);
    }
    for (const json& priority : {json(2147483647), json(-2147483648ll)}) {
        json level = toJson(v);
        level["priority"] = priority;
        EXPECT_EQ(probeVolumeFromJson(level, "level.json", "probes[0]").priority,
                  priority.get<int>());
    }
}

} // namespace
} // namespace specula
