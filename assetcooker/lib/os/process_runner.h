#pragma once
// Runs external commands (the Slurm clients sbatch, squeue, scancel) for the cooker, behind an
// interface so tests can stand in for the scheduler without one.
#include <string>
#include <vector>

namespace specula {

struct ProcessResult {
    int status = 0;     // the exit status; 127 when the program could not be run
    std::string output; // stdout and stderr together
};

class ProcessRunner {
public:
    virtual ~ProcessRunner() = default;
    // Runs argv[0] (looked up in PATH) with the arguments; waits for it.
    virtual ProcessResult run(const std::vector<std::string>& argv) = 0;
    // Waits between two looks at the scheduler (SystemProcessRunner's ends at a cancel request).
    virtual void pause(double seconds) = 0;
};

// The real one: a shell-quoted command line through popen.
class SystemProcessRunner : public ProcessRunner {
public:
    ProcessResult run(const std::vector<std::string>& argv) override;
    void pause(double seconds) override;
};

// `text` single-quoted for a POSIX shell.
std::string shellQuote(const std::string& text);

} // namespace specula
