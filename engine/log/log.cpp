#include "log.h"

#include <spdlog/sinks/stdout_sinks.h>

namespace specula {

spdlog::logger& log() {
    // Created once, on first use; not registered globally, so a host application's own
    // spdlog set-up is left alone.
    static spdlog::logger logger = [] {
        spdlog::logger l("specula", std::make_shared<spdlog::sinks::stderr_sink_mt>());
        l.set_pattern("%n: %v"); // the old fprintf lines, word for word
        return l;
    }();
    return logger;
}

} // namespace specula
