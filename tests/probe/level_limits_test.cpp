// The level twin refuses what the level shader cannot draw (issue 34): more probes than the
// uniform block holds (kMaxLevelProbes). It used to read them, so a measurement could report
// a level no view ever draws.
#include "components/reflection_probe/distance/distance_level_cpu.h"
#include "components/reflection_probe/level_index.h"
#include "engine/core/error.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <unistd.h>

namespace specula {
namespace {

TEST(LevelLimits, TheTwinRefusesMoreProbesThanTheShaderHolds) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                      ("specula-level-limits-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    LevelIndex index;
    index.source = "scene.gltf";
    index.flavour = "distance";
    for (int i = 0; i < 65; ++i) {
        LevelProbeEntry e;
        e.volume.name = "p";
        e.volume.name += std::to_string(i);
        e.volume.position = glm::vec3(float(i), 0.f, 0.f);
        e.volume.proxy = e.volume.influence.box =
            Aabb{e.volume.position - glm::vec3(1.f), e.volume.position + glm::vec3(1.f)};
        e.folder = e.volume.name;
        index.probes.push_back(e);
    }
    const std::string path = (dir / "level.json").string();
    writeLevelIndex(index, path);
    try {
        CpuDistanceLevel level(path, DistanceProbe{DistanceMethod::Secant}, false);
        ADD_FAILURE() << "a 65-probe level was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(path + ": probes: the level has 65 probes; a level "
                                                    "holds 1 to 64"),
                  std::string::npos)
            << e.what();
    }
    std::filesystem::remove_all(dir);
}

// A level bakes distance or light-field probes only; a level.json naming another flavour (a
// farm's PEM shard list holds one) is refused where it is read as a level, naming the field.
TEST(LevelLimits, ALevelOfAnotherFlavourIsRefused) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                      ("specula-level-flavour-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    LevelIndex index;
    index.source = "scene.gltf";
    LevelProbeEntry e;
    e.volume.name = e.folder = "p";
    e.volume.proxy = e.volume.influence.box = Aabb{glm::vec3(-1.f), glm::vec3(1.f)};
    index.probes.push_back(e);
    const std::string path = (dir / "level.json").string();
    for (const char* flavour : {"pem", "Distance", ""}) {
        index.flavour = flavour;
        writeLevelIndex(index, path);
        try {
            readLevelIndex(path);
            ADD_FAILURE() << "a level of flavour '" << flavour << "' was read";
        } catch (const Error& err) {
            EXPECT_NE(std::string(err.what())
                          .find(path + ": flavour: expected \"distance\" or "
                                       "\"lightfield\""),
                      std::string::npos)
                << err.what();
        }
    }
    for (const char* flavour : {"distance", "lightfield"}) {
        index.flavour = flavour;
        writeLevelIndex(index, path);
        EXPECT_EQ(readLevelIndex(path).flavour, flavour);
    }
    std::filesystem::remove_all(dir);
}

} // namespace
} // namespace specula
