#include "output_file.h"

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
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const int error = n < 0 ? errno : EIO;
            ::close(fd);
            fail(error, " (" + std::to_string(done) + " of " + std::to_string(bytes.size()) +
                            " bytes written)");
        }
        done += std::size_t(n);
    }
    if (::close(fd) != 0) fail(errno, " (on close)");
}

} // namespace specula
