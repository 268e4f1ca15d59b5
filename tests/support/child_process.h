#pragma once
// Runs a built tool as a child process the way a user or a script would, with what the
// output-safety tests need beyond popen: extra environment variables, a file-size limit
// (RLIMIT_FSIZE with SIGXFSZ ignored, so a write past it fails with EFBIG exactly as on a
// full disk, without root), and signals sent while the child runs.
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace specula::test {

struct ChildOptions {
    std::vector<std::string> env; // NAME=VALUE, added to this process's environment
    long long fileSizeLimit = -1; // bytes; negative: no limit
};

struct ChildResult {
    int status = -1; // exit code, or 128 + signal
    std::string out, err;
};

inline std::string slurpFile(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

class Child {
public:
    // stdout and stderr go to files under `scratch` (which must exist).
    Child(const std::filesystem::path& exe, std::vector<std::string> args,
          const std::filesystem::path& scratch, const ChildOptions& o = {})
        : outFile_(scratch / "child.out"), errFile_(scratch / "child.err") {
        args.insert(args.begin(), exe.string());
        std::vector<std::string> env = o.env;
        for (char** e = environ; *e; ++e)
            env.emplace_back(*e);
        // Everything the child needs is built before fork: after it only syscalls.
        std::vector<char*> argv, envp;
        for (std::string& a : args)
            argv.push_back(a.data());
        argv.push_back(nullptr);
        for (std::string& e : env)
            envp.push_back(e.data());
        envp.push_back(nullptr);
        const std::string outPath = outFile_.string(), errPath = errFile_.string();
        const rlimit limit{rlim_t(o.fileSizeLimit), rlim_t(o.fileSizeLimit)};
        pid_ = ::fork();
        if (pid_ == 0) {
            const int out = ::open(outPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            const int err = ::open(errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            if (out < 0 || err < 0 || ::dup2(out, 1) < 0 || ::dup2(err, 2) < 0) ::_exit(126);
            if (o.fileSizeLimit >= 0) {
                ::signal(SIGXFSZ, SIG_IGN);
                if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) ::_exit(126);
            }
            ::execve(argv[0], argv.data(), envp.data());
            ::_exit(127);
        }
    }
    Child(const Child&) = delete;
    Child& operator=(const Child&) = delete;
    ~Child() {
        if (pid_ > 0 && status_ < 0) {
            ::kill(pid_, SIGKILL);
            wait();
        }
    }

    pid_t pid() const { return pid_; }
    void signal(int sig) const { ::kill(pid_, sig); }

    // Polls until `ready()` holds or the child has exited; false on timeout or exit.
    template <class Pred> bool waitFor(Pred ready, double seconds) {
        const auto until =
            std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
        while (std::chrono::steady_clock::now() < until) {
            if (ready()) return true;
            int st = 0;
            if (::waitpid(pid_, &st, WNOHANG) == pid_) {
                status_ = decode(st);
                return false;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
        }
        return false;
    }

    ChildResult wait() {
        if (status_ < 0) {
            int st = 0;
            ::waitpid(pid_, &st, 0);
            status_ = decode(st);
        }
        return {status_, slurpFile(outFile_), slurpFile(errFile_)};
    }

private:
    static int decode(int st) {
        return WIFEXITED(st) ? WEXITSTATUS(st) : WIFSIGNALED(st) ? 128 + WTERMSIG(st) : -1;
    }
    std::filesystem::path outFile_, errFile_;
    pid_t pid_ = -1;
    int status_ = -1;
};

inline ChildResult runChild(const std::filesystem::path& exe, const std::vector<std::string>& args,
                            const std::filesystem::path& scratch, const ChildOptions& o = {}) {
    return Child(exe, args, scratch, o).wait();
}

// A PID that certainly belonged to a process that has ended (a child, reaped).
inline pid_t deadPid() {
    const pid_t pid = ::fork();
    if (pid == 0) ::_exit(0);
    int st = 0;
    ::waitpid(pid, &st, 0);
    return pid;
}

} // namespace specula::test
