#pragma once
// Who made a temporary folder beside an output (DIR.tmp-PID, where a probe folder is staged;
// DIR.old-PID, where the previous probe waits during a swap): the owner file inside it,
// written first, names the host and the process ("host H\npid P\n"). A process id means
// something only on its own host: on a disk shared by a cluster, a folder named for a pid
// that does not run here may belong to a live process on another machine. So a stale
// temporary is removed only when its owner file names this host and a process that no longer
// runs (and the caller holds the output's lock: no other writer of it runs anywhere). A
// temporary *file* (file_write.h) names its host and process in its name, PATH.tmp-HOST-PID,
// and is judged the same way.
#include <filesystem>
#include <string>

namespace specula {

inline constexpr const char* kTemporaryOwnerFile = ".specula-owner";

// Whether process `pid` of this host runs (this process does; one of another user counts).
bool processRunsHere(long long pid);

// Writes `folder`/.specula-owner naming this host and process.
void writeTemporaryOwner(const std::filesystem::path& folder);

// Why process `pid` of `host` may still run ("" when it provably does not: it is this host's
// and no longer runs): another host cannot be asked, and a live process is not gone.
std::string whyOwnerMayRun(const std::string& host, long long pid);

// Why the temporary `folder`, named for process `pid`, must be left alone ("" when it is stale:
// its owner file names this host and `pid`, which no longer runs): no owner file, another
// host, another process, or a process that still runs.
std::string whyTemporaryIsNotStale(const std::filesystem::path& folder, long long pid);

} // namespace specula
