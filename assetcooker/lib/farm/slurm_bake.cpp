#include "assetcooker/lib/farm/slurm_bake.h"

#include "assetcooker/lib/farm/shard_bake.h"
#include "assetcooker/lib/os/output_lock.h"
#include "components/reflection_probe/writer/probe_folder.h"
#include "engine/core/error.h"
#include "engine/core/file_write.h"
#include "engine/core/progress.h"
#include "engine/core/regular_file.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>

namespace specula {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

// Where a job's story ends: the shard is in the store or it never will be from this job.
const std::set<std::string> kEndStates = {"COMPLETED", "FAILED",      "CANCELLED",     "TIMEOUT",
                                          "NODE_FAIL", "PREEMPTED",   "OUT_OF_MEMORY", "BOOT_FAIL",
                                          "DEADLINE",  "SPECIAL_EXIT"};
constexpr const char* kGone = "GONE"; // no longer listed by squeue (past MinJobAge)
constexpr int kCancelLooks = 120;     // how many polls a cancel waits for its jobs to end

double since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string joinIndices(const std::vector<int>& indices) {
    std::string s;
    for (const int i : indices) {
        if (!s.empty()) s.push_back(',');
        s.append(std::to_string(i));
    }
    return s;
}

// A job's log ("" when it is missing or no regular file: a planted FIFO must not hang us).
std::string readText(const fs::path& file) {
    try {
        return readRegularFile(file.string(), std::uint64_t(64) << 20);
    } catch (const Error&) {
        return "";
    }
}

std::string lastLines(const std::string& text, int count) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (!line.empty()) lines.push_back(line);
    std::string tail;
    for (std::size_t i = lines.size() > std::size_t(count) ? lines.size() - std::size_t(count) : 0;
         i < lines.size(); ++i)
        tail += lines[i] + "\n";
    return tail;
}

class SlurmBake {
public:
    SlurmBake(const std::string& dir, const SlurmOptions& o, ProcessRunner& runner,
              std::ostream* log)
        : dir_(fs::absolute(dir)), o_(o), runner_(runner), log_(log),
          slurmDir_(fs::path(shardStore(dir_.string())) / "slurm"),
          list_(readShardList(dir_.string())) {
        if (o_.cook.empty()) o_.cook = fs::read_symlink("/proc/self/exe").string();
        fs::create_directories(slurmDir_ / "logs");
        const std::string d = shellQuote(dir_.string()), cook = shellQuote(o_.cook);
        // The jobs run under this bake's output lock (output_lock.h).
        const std::string head =
            "#!/bin/bash\n# Written by specula-cook bake --slurm.\n" +
            (o_.lockHolder.empty() ? std::string()
                                   : "export " + std::string(kLockHolderVariable) + "=" +
                                         shellQuote(o_.lockHolder) + "\n");
        writeFileAtomically((slurmDir_ / "shard.sh").string(),
                            head + "exec " + cook + " bake-shard " + d +
                                " --shard \"$SLURM_ARRAY_TASK_ID\"\n");
        // The dependents' tasks are bake-shard too; a script of their own names them in
        // squeue and the logs.
        writeFileAtomically((slurmDir_ / "dependent.sh").string(),
                            head + "exec " + cook + " bake-shard " + d +
                                " --shard \"$SLURM_ARRAY_TASK_ID\"\n");
        writeFileAtomically((slurmDir_ / "merge.sh").string(),
                            head + "exec " + cook + " merge " + d + "\n");
    }

    SlurmBakeResult run() {
        const auto start = Clock::now();
        // The leaves first, then the final shards with dependencies (light-field probes, PEM
        // samples) as a second array once the first succeeded, then the merge.
        std::vector<int> pending = leafShardsToBake(dir_.string(), list_);
        tracked_ = pending;
        for (const int i : dependentShardsToBake(dir_.string(), list_))
            tracked_.push_back(i);
        std::size_t leafCount = 0;
        for (std::size_t i = 0; i < list_.shards.size(); ++i)
            leafCount += shardDependencies(list_, int(i)).empty() ? 1 : 0;
        if (log_ && pending.size() < leafCount)
            *log_ << leafCount - pending.size() << " of " << leafCount
                  << " leaf shards already in the store (or not needed): not resubmitted\n";
        std::unique_ptr<ProgressBar> bar;
        if (o_.progress) bar = std::make_unique<ProgressBar>("shards on slurm");
        for (int attempt = 0;; ++attempt) {
            const std::vector<int> dependents = dependentShardsToBake(dir_.string(), list_);
            std::string array, second;
            stopIfCancelled();
            if (!pending.empty()) array = submitArray(pending, "shard.sh", "");
            stopIfCancelled();
            if (!dependents.empty()) second = submitArray(dependents, "dependent.sh", array);
            stopIfCancelled();
            const std::string merge = submitMerge(second.empty() ? array : second);
            if (!pending.empty()) {
                const std::map<int, std::string> states = follow(array, pending, bar.get());
                result_.shardWallSeconds = since(start);
                pending = failedOf(array, states, attempt);
            }
            if (pending.empty() && !second.empty()) {
                const std::map<int, std::string> states = follow(second, dependents, bar.get());
                result_.shardWallSeconds = since(start);
                pending = failedOf(second, states, attempt);
            } else if (!second.empty()) {
                cancel(second, "the leaf shards failed");
            }
            if (pending.empty()) {
                finishMerge(merge);
                break;
            }
            cancel(merge, "shards failed");
            // A failed dependent reruns in the next second array, after any leaf it needs.
            std::erase_if(pending, [&](int i) { return !shardDependencies(list_, i).empty(); });
            if (attempt >= o_.retries) break;
            if (log_)
                *log_ << "resubmitting the failed shards (retry " << attempt + 1 << " of "
                      << o_.retries << ")\n";
        }
        bar.reset();
        if (!result_.merged) stopIfCancelled(); // a merge that completed stands
        if (!result_.failures.empty()) result_.merged = false;
        result_.seconds = since(start);
        return result_;
    }

private:
    bool present(int index) const {
        return shardPresent(dir_.string(), list_.shards[std::size_t(index)]);
    }

    fs::path shardLog(int index, const std::string& job) const {
        return slurmDir_ / "logs" / ("shard-" + std::to_string(index) + "-job" + job + ".log");
    }

    std::string submit(std::vector<std::string> argv, const std::string& script) {
        argv.insert(argv.begin(),
                    {"sbatch", "--parsable", "--chdir=" + fs::current_path().string()});
        if (!o_.partition.empty()) argv.push_back("--partition=" + o_.partition);
        if (!o_.time.empty()) argv.push_back("--time=" + o_.time);
        argv.push_back((slurmDir_ / script).string());
        const ProcessResult r = runner_.run(argv);
        const std::string id = r.output.substr(0, r.output.find_first_of(";\n"));
        if (r.status != 0 || id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
            throw Error("", "sbatch",
                        "refused " + script + " (exit status " + std::to_string(r.status) +
                            "): " + lastLines(r.output, 3));
        result_.jobs.push_back(id);
        return id;
    }

    // An array job over `shards` running `script`, after job `after` succeeds (none: "").
    std::string submitArray(const std::vector<int>& shards, const std::string& script,
                            const std::string& after) {
        std::string spec = "--array=" + joinIndices(shards);
        if (o_.maxParallel > 0) spec += "%" + std::to_string(o_.maxParallel);
        std::vector<std::string> argv = {
            script == "shard.sh" ? "--job-name=specula-shards" : "--job-name=specula-dependents",
            spec, "--output=" + (slurmDir_ / "logs" / "shard-%a-job%A.log").string()};
        if (!after.empty()) argv.push_back("--dependency=afterok:" + after);
        const std::string id = submit(argv, script);
        (script == "shard.sh" ? result_.arrays : result_.dependentArrays).push_back(shards);
        if (log_)
            *log_ << "submitted array job " << id << ": shards " << joinIndices(shards)
                  << (after.empty() ? "" : " (after job " + after + " succeeds)") << "\n";
        return id;
    }

    std::string submitMerge(const std::string& array) {
        std::vector<std::string> argv = {"--job-name=specula-merge",
                                         "--output=" +
                                             (slurmDir_ / "logs" / "merge-job%j.log").string()};
        if (!array.empty()) argv.push_back("--dependency=afterok:" + array);
        const std::string id = submit(argv, "merge.sh");
        if (log_)
            *log_ << "submitted merge job " << id
                  << (array.empty() ? "" : " (after job " + array + " succeeds)") << "\n";
        return id;
    }

    // squeue's states of `job` ("" for a single job, task index -> state for an array);
    // `listed` says whether squeue knows the job at all.
    std::map<int, std::string> states(const std::string& job, bool& listed) {
        const ProcessResult r = runner_.run(
            {"squeue", "--noheader", "--array", "--states=all", "--jobs=" + job, "--format=%i|%T"});
        std::map<int, std::string> s;
        listed = false;
        if (r.status != 0) return s; // an unknown job id: past MinJobAge
        std::istringstream lines(r.output);
        for (std::string line; std::getline(lines, line);) {
            const std::size_t bar = line.find('|');
            if (bar == std::string::npos) continue;
            const std::string id = line.substr(0, bar), state = line.substr(bar + 1);
            if (id == job) {
                listed = true;
                s[-1] = state;
            } else if (id.rfind(job + "_", 0) == 0) {
                listed = true;
                const std::string task = id.substr(job.size() + 1);
                if (!task.empty() && task.find_first_not_of("0123456789") == std::string::npos)
                    s[std::stoi(task)] = state;
            }
        }
        return s;
    }

    // Polls until every task of `array` has ended; returns their last states.
    std::map<int, std::string> follow(const std::string& array, const std::vector<int>& shards,
                                      ProgressBar* bar) {
        std::map<int, std::string> last;
        for (;;) {
            stopIfCancelled();   // first: a signal also ends the squeue it interrupts
            bool listed = false; // unused: a task not listed has ended, whatever the array
            const std::map<int, std::string> now = states(array, listed);
            bool running = false;
            for (const int i : shards) {
                const auto it = now.find(i);
                // A pending task cancelled leaves the queue at once (it never had a job of
                // its own; ended ones stay listed for MinJobAge); any other task that is no
                // longer listed ended long ago.
                if (kEndStates.count(last[i])) continue; // ended: stays so
                std::string state = it != now.end()                           ? it->second
                                    : last[i].empty() || last[i] == "PENDING" ? "CANCELLED"
                                                                              : kGone;
                if (state != kGone && !kEndStates.count(state)) running = true;
                if (last[i] != state && (kEndStates.count(state) || state == kGone) && log_)
                    *log_ << "shard " << i << ": " << state << "\n";
                last[i] = state;
            }
            if (bar && !tracked_.empty()) {
                std::size_t done = 0;
                for (const int i : tracked_)
                    done += present(i) ? 1 : 0;
                bar->update(double(done) / double(tracked_.size()));
            }
            if (!running) return last;
            stopIfCancelled();
            runner_.pause(o_.pollSeconds);
            stopIfCancelled();
        }
    }

    // The shards of `array` not in the store; the last attempt's become failures.
    std::vector<int> failedOf(const std::string& array, const std::map<int, std::string>& states,
                              int attempt) {
        std::vector<int> failed;
        for (const auto& [i, state] : states) {
            const fs::path logFile = shardLog(i, array);
            const std::string text = readText(logFile);
            if (present(i) && (state == "COMPLETED" || state == kGone)) {
                const std::size_t at = text.find(": baked in ");
                if (at != std::string::npos) {
                    result_.shardComputeSeconds += std::stod(text.substr(at + 11));
                    ++result_.shardsBaked;
                }
                continue;
            }
            failed.push_back(i);
            if (attempt < o_.retries) continue;
            SlurmShardFailure f;
            f.index = i;
            const Shard& shard = list_.shards[std::size_t(i)];
            f.probe = list_.level.probes[std::size_t(shard.probe)].volume.name;
            f.part = shard.kind == kProbeShard ? -1 : shard.part;
            f.label = shardLabel(list_, i);
            f.state = state == kGone         ? "UNKNOWN (left the queue without its shard)"
                      : state == "COMPLETED" ? "COMPLETED without its shard in the store"
                                             : state;
            f.log = logFile.string();
            std::error_code ec;
            f.logTail = fs::exists(logFile, ec) ? lastLines(text, 5) : "(no log: never started)";
            result_.failures.push_back(f);
        }
        return failed;
    }

    void finishMerge(const std::string& merge) {
        std::string state;
        for (;;) {
            stopIfCancelled();
            bool listed = false;
            const std::map<int, std::string> s = states(merge, listed);
            state = listed ? s.at(-1) : kGone;
            if (state == kGone || kEndStates.count(state)) break;
            stopIfCancelled();
            runner_.pause(o_.pollSeconds);
            stopIfCancelled();
        }
        result_.mergeLog = (slurmDir_ / "logs" / ("merge-job" + merge + ".log")).string();
        const std::string text = readText(result_.mergeLog);
        if (state == kGone)
            state = text.find("merged ") != std::string::npos ? "COMPLETED" : "UNKNOWN";
        result_.mergeState = state;
        result_.merged = state == "COMPLETED";
        if (log_) *log_ << "merge job " << merge << ": " << state << "\n";
    }

    // On a cancel request (SIGINT/SIGTERM): every job this bake submitted is cancelled
    // (scancel, the merge with them: it never runs), waited for until none runs, and Cancelled
    // is thrown naming them. A second request while waiting stops the wait.
    void stopIfCancelled() {
        if (!cancelRequested()) return;
        std::string ids;
        for (const std::string& job : result_.jobs)
            ids += (ids.empty() ? "" : ", ") + job;
        if (result_.jobs.empty())
            throw Cancelled(dir_.string(), "",
                            "interrupted by a signal before any job was submitted; nothing was "
                            "merged");
        std::vector<std::string> argv = {"scancel"};
        argv.insert(argv.end(), result_.jobs.begin(), result_.jobs.end());
        const ProcessResult r = runner_.run(argv);
        if (log_)
            *log_ << "cancelling jobs " << ids << " (interrupted)"
                  << (r.status == 0 ? "" : ": scancel said " + lastLines(r.output, 2)) << "\n";
        clearCancelRequest();
        std::vector<std::string> running = result_.jobs;
        for (int look = 0; !running.empty() && !cancelRequested(); ++look) {
            std::erase_if(running, [&](const std::string& job) {
                bool listed = false;
                for (const auto& [task, state] : states(job, listed))
                    if (!kEndStates.count(state)) return false;
                return true;
            });
            if (running.empty() || look >= kCancelLooks) break;
            runner_.pause(o_.pollSeconds);
        }
        requestCancel();
        std::string still;
        for (const std::string& job : running)
            still += (still.empty() ? "" : ", ") + job;
        throw Cancelled(
            dir_.string(), "",
            "interrupted by a signal: cancelled jobs " + ids + " (scancel)" +
                (still.empty() ? " and waited for them to end" : "; still ending: " + still) +
                "; nothing was merged (a re-run resumes from the shards in the store)");
    }

    void cancel(const std::string& job, const char* why) {
        runner_.run({"scancel", job}); // it may have ended already: nothing to report
        if (log_) *log_ << "cancelled job " << job << " (" << why << ")\n";
    }

    fs::path dir_;
    SlurmOptions o_;
    ProcessRunner& runner_;
    std::ostream* log_;
    fs::path slurmDir_;
    ShardList list_;
    std::vector<int> tracked_; // the shards the first submission runs (the progress bar's)
    SlurmBakeResult result_;
};

} // namespace

SlurmBakeResult bakeOnSlurm(const std::string& dir, const SlurmOptions& options,
                            ProcessRunner& runner, std::ostream* log) {
    return SlurmBake(dir, options, runner, log).run();
}

std::string slurmFailureReport(const SlurmBakeResult& r) {
    std::ostringstream s;
    if (!r.failures.empty()) {
        s << r.failures.size() << " shard" << (r.failures.size() == 1 ? "" : "s")
          << " failed after " << r.arrays.size() << " submissions; nothing was merged:\n";
        for (const SlurmShardFailure& f : r.failures) {
            s << "  shard " << f.index << " (" << (f.label.empty() ? "probe " + f.probe : f.label)
              << "): " << f.state << ", log " << f.log << "\n";
            std::istringstream lines(f.logTail);
            for (std::string line; std::getline(lines, line);)
                s << "    | " << line << "\n";
        }
    } else if (!r.merged) {
        s << "the merge job ended " << r.mergeState << "; see " << r.mergeLog << "\n";
    }
    return s.str();
}

} // namespace specula
