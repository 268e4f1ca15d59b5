#include "temporary_owner.h"

#include "engine/core/error.h"
#include "engine/core/file_write.h"
#include "engine/core/host_name.h"
#include "engine/core/regular_file.h"

#include <cerrno>
#include <signal.h>
#include <sstream>
#include <unistd.h>

namespace specula {

namespace fs = std::filesystem;

// ESRCH: no such process. EPERM means it runs under another user.
bool processRunsHere(long long pid) {
    return pid == ::getpid() || ::kill(pid_t(pid), 0) == 0 || errno != ESRCH;
}

void writeTemporaryOwner(const fs::path& folder) {
    writeFileAtomically((folder / kTemporaryOwnerFile).string(),
                        "host " + hostName() + "\npid " + std::to_string(::getpid()) + "\n");
}

std::string whyTemporaryIsNotStale(const fs::path& folder, long long pid) {
    std::string text;
    try {
        text = readRegularFile((folder / kTemporaryOwnerFile).string(), 4096);
    } catch (const Error&) {
        return "it has no owner file " + std::string(kTemporaryOwnerFile) +
               " (not made by this specula-cook, or its process was killed as it began)";
    }
    std::string host;
    long long owner = -1;
    std::istringstream in(text);
    for (std::string key; in >> key;)
        if (key == "host")
            in >> host;
        else if (key == "pid")
            in >> owner;
    if (host.empty() || owner <= 0)
        return "its owner file " + std::string(kTemporaryOwnerFile) + " names no host and pid";
    if (host == hostName() && owner != pid)
        return "its owner file names process " + std::to_string(owner) + ", not " +
               std::to_string(pid);
    return whyOwnerMayRun(host, owner);
}

std::string whyOwnerMayRun(const std::string& host, long long pid) {
    if (host != hostName())
        return "it belongs to process " + std::to_string(pid) + " on host " + host +
               " (this host cannot tell whether that one still runs)";
    if (processRunsHere(pid)) return "its process " + std::to_string(pid) + " still runs";
    return "";
}

} // namespace specula
