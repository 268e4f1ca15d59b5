#include "assetcooker/lib/os/file_lock.h"

#include <cerrno>
#include <sys/file.h>

namespace specula {

bool tryLockFile(int fd, FileLockMode mode) {
    const int operation = (mode == FileLockMode::Exclusive ? LOCK_EX : LOCK_SH) | LOCK_NB;
    for (;;) {
        if (::flock(fd, operation) == 0) return true;
        if (errno != EINTR) return false;
    }
}

} // namespace specula
