#pragma once
// The one log sink of the project: library code reports what a user may want to know
// (a warning about a scene, a GL debug message) here, never with fprintf. It writes to stderr
// as "specula: message", so a tool's stdout stays its results.
#include <spdlog/logger.h>

namespace specula {

spdlog::logger& log();

} // namespace specula
