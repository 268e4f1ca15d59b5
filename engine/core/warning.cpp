#include "warning.h"

#include <cstdio>
#include <utility>

namespace specula {

namespace {

// A function-local static: set before main() (engine/log registers from a static initialiser)
// without depending on the order globals of different files are constructed in.
WarningHandler& handler() {
    static WarningHandler h;
    return h;
}

} // namespace

void setWarningHandler(WarningHandler h) {
    handler() = std::move(h);
}

void warn(std::string_view message) {
    if (const WarningHandler& h = handler()) {
        h(message);
        return;
    }
    std::fprintf(stderr, "specula: warning: %.*s\n", int(message.size()), message.data());
}

} // namespace specula
