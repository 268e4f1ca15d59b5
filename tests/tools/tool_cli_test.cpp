// The error policy of the tools' command lines (issue 11, item 7), in-process: library code
// names the field it read and the tool names the flag that set it; UsageError is an Error yet
// still exits 2; Cancelled exits 130; any other Error exits 1 with one line; validators refuse
// what the old hand-written parser refused. Every value is strict (issue 34): integers
// decimal, numbers finite, text non-empty, --config a regular file.
#include "assetcooker/lib/cli/tool_cli.h"
#include "engine/core/error.h"
#include "specula/version.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

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

namespace {

// A tool whose `go` takes one option of each kind the tools use; `parsed` holds the values.
struct Values {
    int n = -7;
    std::uint32_t u = 7;
    double x = -7.0;
    std::string name = "unset", sky = "unset";
    std::vector<int> nodes;
};

ToolRun runValues(const std::vector<std::string>& args, Values& parsed) {
    cli::ToolCli tool("tool", "a test tool");
    Values v;
    CLI::App* go =
        tool.addSubcommand("go", "parse", "Parses.", "", [](std::ostream&) { return 0; });
    go->add_option("--n", v.n, "a signed integer")->check(CLI::Range(-100, 100));
    go->add_option("--u", v.u, "an unsigned integer");
    go->add_option("--x", v.x, "a number")->check(CLI::Range(-10.0, 10.0));
    go->add_option("--name", v.name, "a name");
    tool.allowEmpty(go->add_option("--sky", v.sky, "a file, or '' for none"));
    go->add_option("--nodes", v.nodes, "integers")->delimiter(',');
    std::ostringstream out, err;
    ToolRun r;
    r.status = tool.run(args, out, err);
    r.out = out.str();
    r.err = err.str();
    parsed = v;
    return r;
}

} // namespace

TEST(ToolCli, IntegersAreDecimalLeadingZerosIncluded) {
    Values v;
    ASSERT_EQ(runValues({"go", "--n", "010", "--u", "0042", "--nodes", "01,08,010"}, v).status, 0);
    EXPECT_EQ(v.n, 10) << "010 is ten, not octal 8";
    EXPECT_EQ(v.u, 42u);
    EXPECT_EQ(v.nodes, (std::vector<int>{1, 8, 10}));
    ASSERT_EQ(runValues({"go", "--n", "-010"}, v).status, 0);
    EXPECT_EQ(v.n, -10);
    ASSERT_EQ(runValues({"go", "--n", "000"}, v).status, 0);
    EXPECT_EQ(v.n, 0);
    // 0100 is 100 (in range), never octal 64; 0101 is 101 (out of range), never 65.
    ASSERT_EQ(runValues({"go", "--n", "0100"}, v).status, 0);
    EXPECT_EQ(v.n, 100);
    EXPECT_EQ(runValues({"go", "--n", "0101"}, v).status, 2);
}

TEST(ToolCli, IntegersRefuseEverythingButDecimalDigits) {
    Values v;
    for (const char* bad : {"", "0x10", "0b11", "1e2", "+5", " 5", "5 ", "1.0", "--5", "-", "a"}) {
        const ToolRun r = runValues({"go", "--n", bad}, v);
        EXPECT_EQ(r.status, 2) << "'" << bad << "' gave " << v.n;
        EXPECT_NE(r.err.find("--n"), std::string::npos) << r.err;
    }
    for (const char* bad : {"", "-1", "-0", "4294967296", "99999999999999999999999"}) {
        const ToolRun r = runValues({"go", "--u", bad}, v);
        EXPECT_EQ(r.status, 2) << "'" << bad << "' gave " << v.u;
        EXPECT_NE(r.err.find("--u"), std::string::npos) << r.err;
    }
    const ToolRun list = runValues({"go", "--nodes", "1,,"}, v);
    EXPECT_EQ(list.status, 0) << list.err; // empty items between commas are no items
    EXPECT_EQ(runValues({"go", "--nodes", "1,0x2"}, v).status, 2);
    EXPECT_EQ(runValues({"go", "--nodes", ""}, v).status, 2);
}

TEST(ToolCli, NumbersMustBeFiniteEvenWithoutARangeCheck) {
    Values v;
    for (const char* bad : {"nan", "NaN", "inf", "-inf", "infinity", "", "1e999", "0x1p3", "1,5"}) {
        const ToolRun r = runValues({"go", "--x", bad}, v);
        EXPECT_EQ(r.status, 2) << "'" << bad << "' gave " << v.x;
        EXPECT_NE(r.err.find("--x"), std::string::npos) << r.err;
    }
    ASSERT_EQ(runValues({"go", "--x", "-2.5e-1"}, v).status, 0);
    EXPECT_EQ(v.x, -0.25);
}

TEST(ToolCli, TextMustNotBeEmptyUnlessAllowed) {
    Values v;
    const ToolRun r = runValues({"go", "--name", ""}, v);
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.err.find("--name: expected a value, got ''"), std::string::npos) << r.err;
    ASSERT_EQ(runValues({"go", "--sky", ""}, v).status, 0);
    EXPECT_EQ(v.sky, "");
}

TEST(ToolCli, ConfigMustBeARegularFile) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("tool-cli-config-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string fifo = (dir / "fifo").string(), good = (dir / "good.toml").string();
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    std::ofstream(good) << "[go]\nn = 010\nx = 1.5\n";
    Values v;
    ASSERT_EQ(runValues({"--config", good, "go"}, v).status, 0);
    EXPECT_EQ(v.n, 10) << "a config file's integers are decimal too";
    EXPECT_EQ(v.x, 1.5);
    std::ofstream(good) << "[go]\nx = nan\n";
    EXPECT_EQ(runValues({"--config", good, "go"}, v).status, 2) << "gave " << v.x;
    // A FIFO would block the read forever, /dev/zero never ends, a folder reads as nothing.
    const auto start = std::chrono::steady_clock::now();
    for (const std::string& bad : {fifo, std::string("/dev/zero"), dir.string(), std::string()}) {
        for (const bool after : {false, true}) {
            const ToolRun r = after ? runValues({"go", "--config", bad}, v)
                                    : runValues({"--config", bad, "go"}, v);
            EXPECT_EQ(r.status, 2) << "'" << bad << "'";
            EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 2) << r.err;
            EXPECT_NE(r.err.find("--config"), std::string::npos) << r.err;
            EXPECT_NE(r.err.find(bad.empty() ? "''" : bad), std::string::npos) << r.err;
        }
    }
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
    std::filesystem::remove_all(dir);
}

TEST(ToolCli, SizesAreDecimal) {
    int w = 0, h = 0;
    ASSERT_TRUE(cli::parseSize("0100x064", w, h));
    EXPECT_EQ(w, 100) << "0100 is a hundred, not octal 64";
    EXPECT_EQ(h, 64);
    for (const char* bad : {"0x20x32", "32x", "x32", "32x32x", "+32x32", "32 x32", "15x32"})
        EXPECT_FALSE(cli::parseSize(bad, w, h)) << bad;
}
