// Metrics never lie (issue 10): `walk --compare` on the bundled room scaled by 1e6, 1e-6 and 0
// (generated here from assets/room). Those frames used to score PSNR inf: at 1e6 and 1e-6 the
// walk's camera frames no reflector pixel it can compare (nothing measured read as
// "identical"); at 0 the ground truth itself is NaN (a degenerate camera), which folded into
// the same inf.
#include "support/child_process.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using specula::test::runChild;

namespace {

const fs::path kTool = fs::path(SPECULA_BIN_DIR) / "specula-sandbox";
const fs::path kRoomDir = fs::path(SPECULA_SOURCE_DIR) / "assets/room";

struct Scratch {
    fs::path dir = fs::temp_directory_path() /
                   ("specula-metrics-" + std::to_string(::getpid()) + "-" +
                    ::testing::UnitTest::GetInstance()->current_test_info()->name());
    Scratch() {
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    ~Scratch() { fs::remove_all(dir); }
};

// The room with every root node scaled about the origin by `s` (its buffers and textures
// copied beside it).
fs::path scaledRoom(const fs::path& dir, float s) {
    for (const auto& e : fs::directory_iterator(kRoomDir))
        if (e.path().extension() != ".gltf") fs::copy_file(e.path(), dir / e.path().filename());
    std::ifstream in(kRoomDir / "room.gltf");
    nlohmann::json g = nlohmann::json::parse(in);
    for (const auto& r : g["scenes"][g.value("scene", 0)]["nodes"]) {
        nlohmann::json& n = g["nodes"][r.get<std::size_t>()];
        nlohmann::json scale = n.value("scale", nlohmann::json::array({1.0, 1.0, 1.0}));
        for (auto& v : scale)
            v = v.get<double>() * s;
        n["scale"] = scale;
        if (n.contains("translation"))
            for (auto& v : n["translation"])
                v = v.get<double>() * s;
    }
    const fs::path out = dir / "room.gltf";
    std::ofstream(out) << g.dump();
    return out;
}

// The cells of frames.csv's column `name` ("psnr": against the environment-only truth).
std::vector<std::string> psnrCells(const fs::path& csv, const std::string& name = "psnr") {
    std::ifstream in(csv);
    std::string line;
    std::getline(in, line);
    auto split = [](const std::string& text) {
        std::vector<std::string> out;
        std::stringstream s(text);
        for (std::string cell; std::getline(s, cell, ',');)
            out.push_back(cell);
        return out;
    };
    const std::vector<std::string> header = split(line);
    const auto column = std::find(header.begin(), header.end(), name);
    EXPECT_NE(column, header.end()) << name << " missing from " << line;
    if (column == header.end()) return {};
    std::vector<std::string> cells;
    while (std::getline(in, line)) {
        const std::vector<std::string> row = split(line);
        const std::size_t c = std::size_t(column - header.begin());
        cells.push_back(c < row.size() ? row[c] : "");
    }
    return cells;
}

specula::test::ChildResult walk(const fs::path& scene, const fs::path& out,
                                const fs::path& scratch) {
    return runChild(kTool,
                    {"walk", scene.string(), "--headless", "--compare", "--frames", "2", "--size",
                     "64x48", "--face-res", "8", "--out", out.string()},
                    scratch);
}

} // namespace

TEST(WalkMetrics, FramesWithoutReflectorPixelsHaveNoPsnr) {
    for (float s : {1e6f, 1e-6f}) {
        Scratch t;
        const auto r = walk(scaledRoom(t.dir, s), t.dir / "walk", t.dir);
        ASSERT_EQ(r.status, 0) << s << "\n" << r.err;
        for (const char* column : {"psnr", "psnr_full"}) {
            const std::vector<std::string> cells = psnrCells(t.dir / "walk" / "frames.csv", column);
            ASSERT_EQ(cells.size(), 2u);
            for (const std::string& c : cells)
                EXPECT_EQ(c, "none") << "scale " << s << ", " << column
                                     << ": a frame with nothing measured scored " << c;
        }
    }
}

TEST(WalkMetrics, NanGroundTruthIsAnErrorNotAScore) {
    Scratch t;
    const auto r = walk(scaledRoom(t.dir, 0.f), t.dir / "walk", t.dir);
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("NaN"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(t.dir / "walk" / "frames.csv"));
}

TEST(WalkMetrics, TheRoomStillScoresAFiniteNumber) {
    Scratch t;
    const auto r = walk(scaledRoom(t.dir, 1.f), t.dir / "walk", t.dir);
    ASSERT_EQ(r.status, 0) << r.err;
    for (const std::string& c : psnrCells(t.dir / "walk" / "frames.csv"))
        EXPECT_GT(std::stod(c), 12.0) << c;
}
