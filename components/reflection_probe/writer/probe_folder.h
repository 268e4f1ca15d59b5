#pragma once
// Writing a cooked probe folder so that nothing is ever half-written and nothing a user owns
// is ever deleted. `fill` writes every file into a sibling temporary folder DIR.tmp-PID (its
// owner file, temporary_owner.h, written first and removed before the commit) and returns the
// manifest; the manifest goes last and the finished folder takes DIR's place in
// one rename, the only commit point. On any failure, or a cancel requested before that
// rename, DIR is left as it was and the temporary folder is removed.
//
// DIR may only be replaced when it does not exist, is an empty folder, or is a Specula probe
// folder (manifest.json with "format": "specula-probe") that holds nothing but the files
// its manifest lists; never when it holds the input scene.
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>

#include <nlohmann/json.hpp>

namespace specula {

// One process-wide cancel request: a SIGINT/SIGTERM handler sets it (requestCancel is
// async-signal-safe), long loops and every probe write poll it.
void requestCancel() noexcept;
void clearCancelRequest() noexcept;
bool cancelRequested() noexcept;
// Throws Cancelled naming `dir` when a cancel was requested: nothing has been committed.
void throwIfCancelled(const std::string& dir);

// Throws Error naming DIR (and the first foreign file, or the scene) unless a cooked probe
// may replace DIR under the rules above. writeProbeFolder checks it again before it commits.
void checkProbeFolderReplaceable(const std::string& dir, const std::string& sourceScene);

// Repairs what a killed bake (SIGKILL, power loss) left beside DIR: DIR.tmp-PID folders are
// removed, a DIR.old-PID folder is moved back when DIR is missing (the previous probe, caught
// mid-swap) and removed otherwise. Only those whose owner file (temporary_owner.h) names this
// host and a process that no longer runs; any other is left, saying why. One line on `log`
// each. The caller holds DIR's output lock (no other writer of DIR runs).
void removeStaleProbeTemporaries(const std::string& dir, std::ostream& log);
// The same for every X.tmp-PID and X.old-PID folder in `folder` (what a killed merge or level
// bake left beside the probe folders it was replacing).
void removeStaleTemporariesIn(const std::string& folder, std::ostream& log);

// sourceScene: the scene the probe was baked from (a path; need not exist, e.g. "analytic").
void writeProbeFolder(const std::string& dir, const std::string& sourceScene,
                      const std::function<nlohmann::json(const std::filesystem::path& tmp)>& fill);

} // namespace specula
