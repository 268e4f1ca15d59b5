// The error policy of the tools' command lines (issue 11, item 7), in-process: library code
// names the field it read and the tool names the flag that set it; UsageError is an Error yet
// still exits 2; Cancelled exits 130; any other Error exits 1 with one line; validators refuse
// what the old hand-written parser refused.
#include "assetcooker/lib/tool_cli.h"
#include "engine/core/error.h"
#include "specula/version.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

using namespace specula;

namespace {

struct ToolRun {
    int status = -1;
    std::string out, err;
};

// A tool with one subcommand `go` whose action throws what `act` throws.
ToolRun runTool(const std::vector<std::string>& args, std::function<int()> act) {
    cli::ToolCli tool("tool", "a test tool");
    CLI::App* go = tool.addSubcommand("go", "run the action", "The action.", "",
                                      [act](std::ostream&) { return act(); });
    static std::string at;
    go->add_option("--at", at, "a point")->check(cli::vec3Text());
    tool.mapField("face_res", "--face-res");
    std::ostringstream out, err;
    ToolRun r;
    r.status = tool.run(args, out, err);
    r.out = out.str();
    r.err = err.str();
    return r;
}

} // namespace

TEST(ToolCli, UsageErrorIsAnErrorThatStillExitsTwo) {
    static_assert(std::is_base_of_v<Error, UsageError>);
    const ToolRun r = runTool({"go"}, []() -> int { throw UsageError("--at", "needs more"); });
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("tool go: error: --at: needs more"), std::string::npos) << r.err;
}

TEST(ToolCli, LibraryFieldIsReportedAsItsFlag) {
    const ToolRun r =
        runTool({"go"}, []() -> int { throw Error("", "face_res", "expected 1 to 4096, got 0"); });
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("--face-res: expected 1 to 4096"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("face_res"), std::string::npos) << r.err;
    // An error that names a file keeps its field: it is the file's, not a flag's.
    const ToolRun f =
        runTool({"go"}, []() -> int { throw Error("m.json", "face_res", "expected 1 to 4096"); });
    EXPECT_EQ(f.status, 1);
    EXPECT_NE(f.err.find("m.json: face_res: expected"), std::string::npos) << f.err;
}

TEST(ToolCli, CancelledExits130AndOtherFailuresOne) {
    EXPECT_EQ(runTool({"go"}, []() -> int { throw Cancelled("out", "", "stopped"); }).status, 130);
    EXPECT_EQ(runTool({"go"}, []() -> int { throw std::runtime_error("boom"); }).status, 1);
    EXPECT_EQ(runTool({"go"}, [] { return 0; }).status, 0);
}

TEST(ToolCli, ParseErrorsExitTwoNamingTheArgument) {
    for (const char* bad : {"1,2", "nan,0,0", "1e30,0,0", "", ",,", "1,2,3,4"}) {
        const ToolRun r = runTool({"go", "--at", bad}, [] { return 0; });
        EXPECT_EQ(r.status, 2) << bad;
        EXPECT_NE(r.err.find("--at"), std::string::npos) << r.err;
    }
    EXPECT_EQ(runTool({"go", "--at", "1,-2,3e2"}, [] { return 0; }).status, 0);
    const ToolRun extra = runTool({"go", "stray"}, [] { return 0; });
    EXPECT_EQ(extra.status, 2);
    EXPECT_NE(extra.err.find("'stray'"), std::string::npos) << extra.err;
    const ToolRun none = runTool({}, [] { return 0; });
    EXPECT_EQ(none.status, 2);
    EXPECT_NE(none.err.find("missing subcommand"), std::string::npos) << none.err;
}

TEST(ToolCli, FiniteRangeRefusesNanAndTheEnds) {
    const CLI::Validator v = cli::finiteRange(1.0, 2.0);
    for (std::string bad : {"nan", "inf", "0.999", "2.001", "abc", "", "1.5x"})
        EXPECT_FALSE(v(bad).empty()) << bad;
    for (std::string good : {"1", "1.5", "2"})
        EXPECT_TRUE(v(good).empty()) << good;
}

// Every tool answers --version with its name and the project's version (project() in the top
// CMakeLists.txt, through specula/version.h), exit 0, nothing run.
TEST(ToolCli, VersionPrintsTheProjectVersionAndRunsNothing) {
    bool ran = false;
    const ToolRun r = runTool({"--version"}, [&] {
        ran = true;
        return 0;
    });
    EXPECT_EQ(r.status, 0);
    EXPECT_EQ(r.out, std::string("tool ") + SPECULA_VERSION + "\n");
    EXPECT_TRUE(r.err.empty()) << r.err;
    EXPECT_FALSE(ran);
}
