#include "assetcooker/lib/os/output_file.h"

#include "engine/core/error.h"
#include "engine/core/file_write.h"

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace specula {

void writeOutputFile(const std::string& path, std::string_view bytes) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0 || S_ISREG(st.st_mode)) {
        writeFileAtomically(path, bytes);
        return;
    }
    if (S_ISDIR(st.st_mode)) throw Error(path, "", "cannot write: it is a folder");
    auto fail = [&](int error, const std::string& context) {
        throw Error(path, "", std::string("cannot write: ") + std::strerror(error) + context);
    };
    const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) fail(errno, "");
    std::size_t done = 0;
    if (const int error = writeAll(fd, bytes, done)) {
        ::close(fd);
        fail(error, bytesWrittenNote(done, bytes.size()));
    }
    if (::close(fd) != 0) fail(errno, " (on close)");
}

} // namespace specula
