#pragma once
// Shared by the bad-input tests (numerics, image, scene): expecting a refusal that names the
// file and the field, and running a read that may hang (a FIFO, /dev/zero) in a child
// process under a deadline, so a regression fails the test instead of blocking ctest.
#include "engine/core/error.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <iterator>
#include <poll.h>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace specula::test {

inline std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

inline void spit(const std::filesystem::path& p, const std::string& bytes) {
    std::ofstream(p, std::ios::binary | std::ios::trunc) << bytes;
}

// `j` as text with the first value of `key` replaced by `literal`: a number JSON can spell but
// no double holds (1e999), which a json object cannot carry.
inline std::string withRawValue(const nlohmann::json& j, const std::string& key,
                                const std::string& literal) {
    std::string text = j.dump(2);
    const std::string quoted = "\"" + key + "\": ";
    const std::size_t at = text.find(quoted) + quoted.size();
    return text.replace(at, text.find_first_of(",\n", at) - at, literal);
}

// The message of the specula::Error `read` throws; "" (and a test failure) when it returns
// or throws anything else.
inline std::string errorOf(const std::function<void()>& read) {
    try {
        read();
    } catch (const Error& e) {
        return e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << "escaped as a non-specula exception: " << e.what();
        return "";
    }
    ADD_FAILURE() << "accepted";
    return "";
}

// Expects one line that contains every one of `parts` (the file, the field, the reason).
inline void expectNames(const std::string& what, std::initializer_list<std::string> parts) {
    std::printf("[bad-input] %s\n", what.c_str());
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    for (const std::string& part : parts)
        EXPECT_NE(what.find(part), std::string::npos) << "'" << part << "' not in: " << what;
}

// Runs `read` in a child process and returns errorOf(read) as the child saw it. A child still
// running after `seconds` is killed and the test fails: the read blocked or span. The child
// is forked from a process that may have run thread pools (OpenEXR's, TBB's) whose threads
// do not exist in it, so `read` must meet the bad file before it decodes any image.
inline std::string errorOfInChild(const std::function<void()>& read, int seconds = 10) {
    int fds[2];
    if (::pipe(fds) != 0) {
        ADD_FAILURE() << "pipe failed";
        return "";
    }
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::close(fds[0]);
        std::string what;
        try {
            read();
            what = "(accepted)";
        } catch (const Error& e) {
            what = e.what();
        } catch (const std::exception& e) {
            what = std::string("(non-specula exception) ") + e.what();
        }
        (void)!::write(fds[1], what.data(), what.size());
        ::_exit(0);
    }
    ::close(fds[1]);
    std::string out;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
    bool timedOut = false;
    for (;;) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
            deadline - std::chrono::steady_clock::now());
        pollfd p{fds[0], POLLIN, 0};
        if (left.count() <= 0 || ::poll(&p, 1, int(left.count())) == 0) {
            timedOut = true;
            break;
        }
        char buf[4096];
        const ssize_t got = ::read(fds[0], buf, sizeof buf);
        if (got <= 0) break;
        out.append(buf, std::size_t(got));
    }
    ::close(fds[0]);
    if (timedOut) ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    if (timedOut) {
        ADD_FAILURE() << "the read did not return within " << seconds << " s (blocked or spinning)";
        return "";
    }
    EXPECT_EQ(out.rfind("(", 0), std::string::npos) << out;
    return out;
}

} // namespace specula::test
