#include "assetcooker/lib/os/process_runner.h"

#include "components/reflection_probe/writer/probe_folder.h"

#include <chrono>
#include <cstdio>
#include <sys/wait.h>
#include <thread>

namespace specula {

std::string shellQuote(const std::string& text) {
    std::string q = "'";
    for (const char c : text)
        if (c == '\'')
            q.append("'\\''");
        else
            q.push_back(c);
    q.push_back('\'');
    return q;
}

ProcessResult SystemProcessRunner::run(const std::vector<std::string>& argv) {
    std::string line;
    for (const std::string& a : argv) {
        if (!line.empty()) line.push_back(' ');
        line.append(shellQuote(a));
    }
    line.append(" 2>&1");
    ProcessResult r;
    FILE* pipe = popen(line.c_str(), "r");
    if (!pipe) return {127, "could not run " + line};
    char buffer[4096];
    std::size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0)
        r.output.append(buffer, n);
    const int status = pclose(pipe);
    r.status = status < 0 ? 127 : WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return r;
}

void SystemProcessRunner::pause(double seconds) {
    // In short steps: a cancel request (a signal) ends the wait at once.
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (!cancelRequested() && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
}

} // namespace specula
