#include "log.h"

#include "engine/core/warning.h"

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

namespace {

// The runtime's warnings (engine/core/warning.h) go to this log in every program that links
// it: the tools and the tests.
const bool kWarningsRouted = [] {
    setWarningHandler([](std::string_view message) { log().warn("{}", message); });
    return true;
}();

} // namespace

} // namespace specula
