#pragma once
// Runs a built tool through the shell as a user would type it (arguments already quoted),
// capturing stdout, stderr and the exit status; the lines of a file it wrote; and a fresh
// temporary folder per use. What the command-line tests of every tool share.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace specula::test {

struct ToolRun {
    int status = -1; // exit code; -1 when the tool did not exit normally
    std::string out, err;
};

// `s` as one single-quoted shell word.
inline std::string shellQuote(const std::string& s) {
    std::string q = "'";
    for (char c : s)
        q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

// `prefix` goes before the tool (e.g. "ulimit -f 1; "); stderr is read back from a file.
inline ToolRun runShellTool(const std::filesystem::path& tool, const std::string& args,
                            const std::string& prefix = "") {
    const std::filesystem::path errFile =
        std::filesystem::temp_directory_path() /
        (tool.filename().string() + "_test_" + std::to_string(::getpid()) + ".err");
    ToolRun r;
    const std::string cmd =
        prefix + shellQuote(tool.string()) + " " + args + " 2>" + shellQuote(errFile.string());
    FILE* pipe = ::popen(cmd.c_str(), "r");
    if (!pipe) return r;
    char buf[4096];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0)
        r.out.append(buf, n);
    const int st = ::pclose(pipe);
    r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    std::ifstream in(errFile);
    r.err.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    std::filesystem::remove(errFile);
    return r;
}

// One subcommand of a built tool: command(args) runs "TOOL NAME ARGS" (runShellTool).
struct ToolSubcommand {
    std::filesystem::path tool;
    std::string name;

    ToolRun operator()(const std::string& args) const {
        return runShellTool(tool, name + " " + args);
    }
};

// The lines of a text file a tool wrote, without their '\n's; none when it cannot be read.
inline std::vector<std::string> fileLines(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::vector<std::string> out;
    for (std::string line; std::getline(in, line);)
        out.push_back(line);
    return out;
}

// Lines in a tool's output (its '\n's): a one-line error is exactly one.
inline std::size_t lineCount(const std::string& s) {
    std::size_t n = 0;
    for (char c : s)
        n += c == '\n';
    return n;
}

// A fresh folder under the temporary directory, removed with the object (kept when
// SPECULA_KEEP_TEST_OUT is set, to look at what a test wrote).
struct TempDir {
    std::filesystem::path path;
    explicit TempDir(const std::string& name)
        : path(std::filesystem::temp_directory_path() /
               ("specula-" + name + "-" + std::to_string(::getpid()))) {
        std::filesystem::remove_all(path);
        std::filesystem::create_directories(path);
    }
    ~TempDir() {
        if (!std::getenv("SPECULA_KEEP_TEST_OUT")) std::filesystem::remove_all(path);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
};

} // namespace specula::test
