#pragma once
// One writer per output. Every specula-cook command that writes an output folder OUT (bake,
// shards, merge, bake --slurm) holds an exclusive advisory lock (flock) on the file OUT.lock
// beside it for its whole run; bake-shard holds it shared, as its runs share a level by
// design (each computes its own shard into the store, atomically) but must not run beside a
// bake or a merge of it. The lock file names its holders, a line each ("COMMAND host H pid
// P"); a writer that finds the lock held fails at once with an Error naming them. The kernel
// releases the lock of a killed process (the next writer takes the file over); the last
// holder removes the file.
//
// The jobs of a `bake --slurm` run on the submitter's behalf under its lock: it passes its
// holder ("host H pid P") in SPECULA_COOK_LOCK_HOLDER, and a command that finds the lock held
// by exactly that holder goes on without taking it.
#include "assetcooker/lib/os/file_lock.h"

#include <filesystem>
#include <string>

namespace specula {

inline constexpr const char* kLockHolderVariable = "SPECULA_COOK_LOCK_HOLDER";

// OUT's lock file: OUT (absolute, without a trailing separator) + ".lock".
std::string outputLockPath(const std::string& out);

class OutputLock {
public:
    // Takes OUT's lock for `command` (creating OUT's parent folders when missing; removed
    // again with the lock when still empty). Throws Error naming OUT, the holders (command,
    // host, pid) and the lock file when another process holds it.
    OutputLock(const std::string& out, const std::string& command, FileLockMode mode);
    ~OutputLock();
    OutputLock(const OutputLock&) = delete;
    OutputLock& operator=(const OutputLock&) = delete;

    // "host H pid P": this process, the value of SPECULA_COOK_LOCK_HOLDER for its jobs.
    const std::string& holder() const { return holder_; }
    const std::string& path() const { return path_; }
    // Whether this run goes on under its submitter's lock (SPECULA_COOK_LOCK_HOLDER).
    bool onBehalfOfHolder() const { return fd_ < 0; }

private:
    std::string path_, holder_;
    FileLockMode mode_;
    int fd_ = -1;
    std::filesystem::path createdParent_;
};

} // namespace specula
