// What walk and bench leave when a write fails or the input is bad (issue 10, items 4 and
// 11): a write past a file-size limit (EFBIG, as on a full disk) fails the run with an error
// naming the file, never exit 0 over a truncated frame, sheet or csv; a failed run removes
// the --out folder it created and leaves one it did not create (and its user's files).
#include "tests/support/child_process.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using specula::test::ChildOptions;
using specula::test::ChildResult;

namespace {

const fs::path kTool = fs::path(SPECULA_BIN_DIR) / "specula-sandbox";
const fs::path kRoom = fs::path(SPECULA_SOURCE_DIR) / "assets/room/room.gltf";

class SandboxOutputSafety : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        root_ = fs::temp_directory_path() /
                ("specula-sandbox-output-safety-" + std::to_string(::getpid()));
        fs::remove_all(root_);
        fs::create_directories(root_ / "scratch");
        // One small probe for every walk below, baked by an unlimited walk.
        const ChildResult r =
            run({"walk", kRoom.string(), "--headless", "--frames", "1", "--size", "32x24",
                 "--face-res", "16", "--out", (root_ / "first").string()});
        ASSERT_EQ(r.status, 0) << r.err;
        manifest_ = root_ / "first" / "probe" / "manifest.json";
    }
    static void TearDownTestSuite() { fs::remove_all(root_); }

    static ChildResult run(const std::vector<std::string>& args, long long fileSizeLimit = -1) {
        ChildOptions o;
        o.env = {"LP_NUM_THREADS=1"};
        o.fileSizeLimit = fileSizeLimit;
        const ChildResult r = specula::test::runChild(kTool, args, root_ / "scratch", o);
        std::printf("[sandbox-output] %s (file limit %lld): exit %d, stderr: %s", args[0].c_str(),
                    fileSizeLimit, r.status, r.err.empty() ? "(empty)\n" : r.err.c_str());
        return r;
    }
    // Three 160x120 frames (about 8 KB each as PNG) and a contact sheet (about 23 KB).
    static ChildResult walk(const fs::path& out, long long fileSizeLimit) {
        return run({"walk", manifest_.string(), "--headless", "--frames", "3", "--size", "160x120",
                    "--out", out.string()},
                   fileSizeLimit);
    }

    static fs::path root_, manifest_;
};
fs::path SandboxOutputSafety::root_, SandboxOutputSafety::manifest_;

} // namespace

TEST_F(SandboxOutputSafety, ShortWriteOfAFrameFailsTheWalk) {
    const fs::path out = root_ / "frames-fail" / "out";
    const ChildResult r = walk(out, 3000);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("frame_0000.png"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
    EXPECT_EQ(r.out.find("wrote"), std::string::npos) << "no success line over a failure";
    EXPECT_FALSE(fs::exists(root_ / "frames-fail")) << "the folders it created must go";
}

TEST_F(SandboxOutputSafety, ShortWriteOfTheContactSheetFailsTheWalk) {
    // Frames and frames.csv fit under the limit, the contact sheet does not.
    const fs::path out = root_ / "sheet-fail";
    const ChildResult r = walk(out, 15000);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.err.find("contact_sheet.png"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
    // Without the limit the same walk succeeds and its files are whole.
    const ChildResult ok = walk(out, -1);
    EXPECT_EQ(ok.status, 0) << ok.err;
    EXPECT_GT(fs::file_size(out / "contact_sheet.png"), 15000u);
}

TEST_F(SandboxOutputSafety, FailedWalkKeepsAFolderItDidNotCreate) {
    const fs::path out = root_ / "users";
    fs::create_directories(out);
    std::ofstream(out / "notes.txt") << "keep me";
    const ChildResult r = walk(out, 3000);
    EXPECT_EQ(r.status, 1);
    EXPECT_TRUE(fs::exists(out / "notes.txt"));
    for (const auto& e : fs::directory_iterator(out))
        EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos)
            << e.path() << " left behind";
}

TEST_F(SandboxOutputSafety, FailedRunOnBadInputLeavesNoOutputFolder) {
    const fs::path out = root_ / "bad-input";
    EXPECT_EQ(run({"walk", (root_ / "missing.json").string(), "--headless", "--out", out.string()})
                  .status,
              1);
    EXPECT_FALSE(fs::exists(out));
    std::ofstream(root_ / "garbage.gltf") << "not a glTF";
    EXPECT_EQ(run({"bench", "--quick", "--scene", (root_ / "garbage.gltf").string(), "--out",
                   out.string()})
                  .status,
              1);
    EXPECT_FALSE(fs::exists(out));
}
