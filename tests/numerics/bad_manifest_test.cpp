// Bad cooked probes (docs/design.md §8): every malformed manifest or image is refused with one line
// that names the file and the field, and reading never changes the folder.
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "components/reflection_probe/distance/writer/distance_probe_writer.h"
#include "engine/core/error.h"
#include "probe/analytic_probe.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <functional>
#include <unistd.h>

namespace fs = std::filesystem;
using nlohmann::json;
using namespace specula;

namespace {

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

class BadManifest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("specula-bad-manifest-" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        DistanceProbeAsset a = test::makeBoxProbe(test::AnalyticBox{}, 4);
        a.layers[0].method = "bisection";
        writeDistanceProbe(a, (dir_ / "probe").string(), "analytic");
        good_ = json::parse(slurp(dir_ / "probe" / "manifest.json"));
    }
    void TearDown() override { fs::remove_all(dir_); }

    // Writes the mutated manifest, reads it, expects an Error naming `file` and `field`.
    void expectRefused(const std::function<void(json&)>& mutate, const std::string& field,
                       const std::string& file = "manifest.json") {
        json m = good_;
        mutate(m);
        const fs::path path = dir_ / "probe" / "manifest.json";
        std::ofstream(path) << m.dump(2);
        const std::string before = slurp(dir_ / "probe" / "layer_00.ktx2");
        try {
            readDistanceProbe(path.string());
            ADD_FAILURE() << "accepted a manifest with a bad " << field;
        } catch (const Error& e) {
            const std::string what = e.what();
            std::printf("[bad-input] %-14s -> %s\n", field.c_str(), what.c_str());
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
            EXPECT_NE(what.find(file), std::string::npos) << what;
            EXPECT_NE(what.find(field), std::string::npos) << what;
        }
        EXPECT_EQ(slurp(dir_ / "probe" / "layer_00.ktx2"), before);
    }

    fs::path dir_;
    json good_;
};

} // namespace

TEST_F(BadManifest, GoodOneReads) {
    const DistanceProbeAsset a = readDistanceProbe((dir_ / "probe" / "manifest.json").string());
    EXPECT_EQ(a.faceRes, 4);
}

TEST_F(BadManifest, EveryMalformedFieldIsNamed) {
    expectRefused([](json& m) { m["format"]["major"] = 4; }, "format.major"); // newer than 3.x
    expectRefused([](json& m) { m["format"]["major"] = 1; }, "format.major"); // EXR: re-cook
    expectRefused([](json& m) { m["format"]["minor"] = 1.5; }, "format.minor");
    expectRefused([](json& m) { m["format"]["major"] = "2"; }, "format.major");
    expectRefused([](json& m) { m["format"].erase("minor"); }, "format.minor");
    expectRefused([](json& m) { m["format"]["name"] = "other"; }, "format");
    expectRefused([](json& m) { m["format"] = "other"; }, "format");
    // Before 2.1: "format" a string and an integer "version" (the major).
    expectRefused([](json& m) { m["format"] = "specula-probe", m["version"] = 1; }, "version");
    expectRefused([](json& m) { m["format"] = "specula-probe", m["version"] = 4; }, "version");
    expectRefused([](json& m) { m["format"] = "specula-probe"; }, "version");
    expectRefused([](json& m) { m["flavour"] = 3; }, "flavour");
    expectRefused([](json& m) { m["inputs"] = 7; }, "inputs");
    expectRefused(
        [](json& m) {
            m["inputs"] = {{"geometry", 1}, {"options", ""}, {"sky", "none"}};
        },
        "inputs.geometry");
    expectRefused(
        [](json& m) {
            m["inputs"] = {{"geometry", "g"}, {"options", "o"}};
        },
        "inputs.sky");
    expectRefused([](json& m) { m["range_D"] = "far"; }, "range_D");
    expectRefused([](json& m) { m["range_D"] = -1; }, "range_D");
    expectRefused([](json& m) { m["d_inf"] = nullptr; }, "d_inf");
    expectRefused([](json& m) { m["face_res"] = 1e9; }, "face_res");
    expectRefused([](json& m) { m["face_res"] = 5; }, "pixelWidth", "layer_00.ktx2");
    expectRefused([](json& m) { m["centre"] = json::array({1, 2}); }, "centre");
    expectRefused([](json& m) { m["centre"] = json::array({1, "a", 2}); }, "centre");
    expectRefused([](json& m) { m["box"] = 7; }, "box.min");
    expectRefused([](json& m) { m["layers"] = json::object(); }, "layers");
    expectRefused([](json& m) { m["layers"] = json::array(); }, "layers");
    expectRefused(
        [](json& m) {
            json many = json::array();
            for (int i = 0; i < 300; ++i)
                many.push_back(m["layers"][0]);
            m["layers"] = many;
        },
        "layers");
    expectRefused([](json& m) { m["layers"][0]["avg_distance"] = "x"; }, "layers[0].avg_distance");
    expectRefused([](json& m) { m["layers"][0]["solid_angle_sr"] = 99; },
                  "layers[0].solid_angle_sr");
    expectRefused([](json& m) { m["layers"][0]["method"] = "bisect"; }, "layers[0].method");
    expectRefused([](json& m) { m["layers"][0]["method"] = "layered"; }, "layers[0].method");
    expectRefused([](json& m) { m["layers"][0]["file"] = "../etc/passwd"; }, "layers[0].file");
    expectRefused([](json& m) { m["layers"][0]["file"] = "/etc/passwd"; }, "layers[0].file");
    expectRefused([](json& m) { m["layers"][0]["file"] = "missing.ktx2"; }, "layers[0].file");
    expectRefused([](json& m) { m["layers"][0]["checksum"] = "fnv1a64:0000000000000000"; },
                  "layers[0].checksum");
    expectRefused(
        [](json& m) {
            m["sky"] = {{"file", "missing.ktx2"}, {"checksum", "x"}};
        },
        "sky.file");
}

TEST_F(BadManifest, NotJsonAndTruncatedFiles) {
    const fs::path path = dir_ / "probe" / "manifest.json";
    const std::string text = slurp(path);
    for (const std::string& bad : {text.substr(0, text.size() / 2), std::string(""),
                                   std::string("\x89PNG garbage"), std::string(100000, '[')}) {
        std::ofstream(path, std::ios::binary) << bad;
        try {
            readDistanceProbe(path.string());
            ADD_FAILURE() << "accepted a broken manifest";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("manifest.json"), std::string::npos);
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        }
    }
    // A truncated KTX2 whose checksum was updated to match: the image reader must refuse it.
    std::ofstream(path) << text;
    const fs::path exr = dir_ / "probe" / "layer_00.ktx2";
    const std::string bytes = slurp(exr);
    std::ofstream(exr, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    json m = json::parse(text);
    m["layers"][0]["checksum"] = fileChecksum(exr.string());
    std::ofstream(path) << m.dump();
    try {
        readDistanceProbe(path.string());
        ADD_FAILURE() << "accepted a truncated KTX2";
    } catch (const Error& e) {
        std::printf("[bad-input] truncated KTX2  -> %s\n", e.what());
        EXPECT_NE(std::string(e.what()).find("layer_00.ktx2"), std::string::npos) << e.what();
    }
}
