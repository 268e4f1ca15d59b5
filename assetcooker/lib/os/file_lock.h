#pragma once
// An advisory whole-file lock (flock) on an open file descriptor, never waited for: the
// output lock (output_lock.h) is its one user.
namespace specula {

enum class FileLockMode { Shared, Exclusive };

// Locks `fd` in `mode` without waiting: true when locked (a held lock is converted), false when
// another open file holds a conflicting lock. Any other failure: false with errno set (never
// EWOULDBLOCK then).
bool tryLockFile(int fd, FileLockMode mode);

} // namespace specula
