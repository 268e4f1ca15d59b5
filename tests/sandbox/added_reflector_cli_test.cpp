// specula-sandbox walk/bench --add-reflector through the shell: the help names both forms, a
// bad spec is a usage error naming the flag, and a headless walk of a closed room with no
// camera node and no reflector of its own runs once a sphere is dropped into it (the camera
// found inside the room), while a reflector shut in a hollow crate bakes but gets the "no free
// viewpoint" error.
#include "support/shell_tool.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kTool = fs::path(SPECULA_BIN_DIR) / "specula-sandbox";
const fs::path kRoom = fs::path(SPECULA_SOURCE_DIR) / "assets/room/room.gltf";

using specula::test::shellQuote;
using specula::test::ToolRun;

ToolRun tool(const std::string& args, const std::string& prefix = "") {
    return specula::test::runShellTool(kTool, args, prefix);
}

struct TempDir : specula::test::TempDir {
    explicit TempDir(const std::string& name) : specula::test::TempDir("added-reflector-" + name) {}
};

// A 6 x 3 x 6 m closed room (single-sided walls facing in) on the floor y = 0, no camera node
// and no reflector; `crate`: also a closed crate around (0, 1.2, 0), 5 cm thick walls (a 1.2 m
// box facing out, a 1.1 m one facing in): the probe inside it sees its inner walls.
fs::path writeRoom(const fs::path& dir, bool crate) {
    // The unit cube's 12 triangles, counter-clockwise seen from outside; the room's reversed.
    std::vector<float> out, in;
    for (int axis = 0; axis < 3; ++axis)
        for (const float sign : {1.f, -1.f}) {
            const int u = (axis + 1) % 3, w = (axis + 2) % 3;
            std::array<std::array<float, 3>, 4> c{};
            const float su[4] = {-1, 1, 1, -1}, sw[4] = {-1, -1, 1, 1};
            for (int i = 0; i < 4; ++i) {
                c[i][axis] = 0.5f * sign;
                c[i][u] = 0.5f * su[i];
                c[i][w] = 0.5f * sw[i];
            }
            // (u x w) = +axis, so u-then-w corners are counter-clockwise seen from +axis.
            const bool ccwFromOutside = sign > 0.f;
            for (const std::array<int, 3> t : {std::array<int, 3>{0, 1, 2}, {0, 2, 3}}) {
                const std::array<int, 3> fwd = t, rev = {t[0], t[2], t[1]};
                for (const int k : ccwFromOutside ? fwd : rev)
                    out.insert(out.end(), c[k].begin(), c[k].end());
                for (const int k : ccwFromOutside ? rev : fwd)
                    in.insert(in.end(), c[k].begin(), c[k].end());
            }
        }
    std::vector<float> all = out;
    all.insert(all.end(), in.begin(), in.end());
    const std::size_t bytes = all.size() * sizeof(float);
    std::ofstream(dir / "room.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(all.data()), std::streamsize(bytes));
    auto accessor = [](std::size_t offset) {
        std::ostringstream s;
        s << R"({"bufferView":0,"byteOffset":)" << offset
          << R"(,"componentType":5126,"count":36,"type":"VEC3",)"
          << R"("min":[-0.5,-0.5,-0.5],"max":[0.5,0.5,0.5]})";
        return s.str();
    };
    std::ostringstream j;
    const std::string crateNodes =
        R"(,{"name":"crate","mesh":0,"translation":[0,1.2,0],"scale":[1.2,1.2,1.2]})"
        R"(,{"name":"crate_inside","mesh":1,"translation":[0,1.2,0],"scale":[1.1,1.1,1.1]})";
    j << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0)" << (crate ? ",1,2" : "")
      << R"(]}],"nodes":[{"name":"room","mesh":1,"translation":[0,1.5,0],"scale":[6,3,6]})"
      << (crate ? crateNodes : "")
      << R"(],"meshes":[{"primitives":[{"attributes":{"POSITION":0},"material":0}]},)"
      << R"({"primitives":[{"attributes":{"POSITION":1},"material":0}]}],)"
      << R"("materials":[{"name":"plaster","pbrMetallicRoughness":{"baseColorFactor":)"
      << R"([0.7,0.7,0.7,1],"metallicFactor":0,"roughnessFactor":1}}],)"
      << R"("buffers":[{"uri":"room.bin","byteLength":)" << bytes << "}],"
      << R"("bufferViews":[{"buffer":0,"byteLength":)" << bytes << "}],"
      << R"("accessors":[)" << accessor(0) << "," << accessor(out.size() * sizeof(float)) << "]}";
    const fs::path path = dir / (crate ? "crate_room.gltf" : "room.gltf");
    std::ofstream(path) << j.str();
    return path;
}

using specula::test::lineCount;

} // namespace

TEST(SandboxAddReflector, HelpExplainsBothForms) {
    for (const char* sub : {"walk --help", "bench --help"}) {
        const ToolRun r = tool(sub);
        ASSERT_EQ(r.status, 0) << sub << ": " << r.err;
        EXPECT_NE(r.out.find("--add-reflector"), std::string::npos) << sub;
        EXPECT_NE(r.out.find("sphere:x,y,z,r"), std::string::npos) << sub;
        EXPECT_NE(r.out.find("box:x,y,z,sx,sy,sz"), std::string::npos) << sub;
        EXPECT_NE(r.out.find("sphere:0,1.2,0,0.3"), std::string::npos) << sub; // an example
    }
}

TEST(SandboxAddReflector, BadSpecIsAUsageErrorNamingTheFlag) {
    const std::string room = shellQuote(kRoom.string());
    for (const std::string& args : std::vector<std::string>{
             "walk " + room + " --add-reflector cone:0,1,0,1",
             "walk " + room + " --add-reflector sphere:0,1,0",
             "walk " + room + " --add-reflector sphere:0,1,0,0.3 --add-reflector box:0,1,0,1,1",
             "walk " + room + " --add-reflector sphere:0,nan,0,1",
             "walk " + room + " --add-reflector", "bench --add-reflector sphere:0,1,0,-1",
             "bench --add-reflector box:0,1,0,1,0,1"}) {
        const ToolRun r = tool(args);
        EXPECT_EQ(r.status, 2) << "'" << args << "': " << r.err;
        EXPECT_NE(r.err.find("--add-reflector"), std::string::npos) << args << ": " << r.err;
        EXPECT_TRUE(r.out.empty()) << args;
    }
}

TEST(SandboxAddReflector, HeadlessWalkOfARoomWithAnAddedSphere) {
    TempDir dir("walk");
    const fs::path room = writeRoom(dir.path, false);
    const std::string walk = "walk " + shellQuote(room.string()) +
                             " --headless --frames 2 --size 64x48 --face-res 16 --compare";

    // Without a reflector the scene has nothing to walk.
    const ToolRun none = tool(walk + " --out " + shellQuote((dir.path / "none").string()));
    EXPECT_EQ(none.status, 1) << none.err;
    EXPECT_NE(none.err.find("no reflector"), std::string::npos) << none.err;

    const fs::path out = dir.path / "out";
    const ToolRun r =
        tool(walk + " --add-reflector sphere:0,1.2,0,0.3 --out " + shellQuote(out.string()));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("added added_reflector_0 (sphere:0,1.2,0,0.3)"), std::string::npos)
        << r.out;
    // The camera stands inside the room (the old default, 3.5 m out on +Z, is outside).
    const std::size_t at = r.out.find("camera at ");
    ASSERT_NE(at, std::string::npos) << r.out;
    std::istringstream eyeText(r.out.substr(at + 10));
    double x = 0, y = 0, z = 0;
    char comma = 0;
    eyeText >> x >> comma >> y >> comma >> z;
    EXPECT_TRUE(std::abs(x) < 3 && y > 0 && y < 3 && std::abs(z) < 3) << r.out;

    // Every frame sees the sphere: a PSNR, not "none".
    std::ifstream csv(out / "frames.csv");
    std::string line;
    std::getline(csv, line);
    ASSERT_NE(line.find("psnr"), std::string::npos) << line;
    int frames = 0;
    while (std::getline(csv, line)) {
        ++frames;
        EXPECT_EQ(line.find("none"), std::string::npos) << line;
    }
    EXPECT_EQ(frames, 2);
}

TEST(SandboxAddReflector, ReflectorInACrateHasNoFreeViewpoint) {
    TempDir dir("crate");
    const fs::path room = writeRoom(dir.path, true);
    const ToolRun r = tool("walk " + shellQuote(room.string()) +
                           " --headless --frames 1 --size 64x48 --face-res 16 "
                           "--add-reflector sphere:0,1.2,0,0.3 --out " +
                           shellQuote((dir.path / "out").string()));
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("no free viewpoint"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--add-reflector"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(room.string()), std::string::npos) << r.err;
}
