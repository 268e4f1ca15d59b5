#pragma once
// This machine's name, as the writers of shared folders record it beside their process id (a
// lock file's holder, a temporary folder's owner, a temporary file's name): a process id
// means something only on the host that issued it. Header-only, like file_write.h, which
// names temporary files with it.
#include <string>

#include <unistd.h>

namespace specula {

// gethostname's answer; "localhost" when it has none.
inline std::string hostName() {
    char name[256] = {};
    if (::gethostname(name, sizeof name - 1) != 0 || name[0] == '\0') return "localhost";
    return name;
}

} // namespace specula
