#pragma once
// The runtime's one warning channel: what a reader finds worth a user's attention that does
// not stop it (an asset of a newer minor format, members it ignores). A host engine routes it
// into its own log with setWarningHandler; until then it goes to stderr as
// "specula: warning: <message>". The tools route it into their log (engine/log).
#include <functional>
#include <string_view>

namespace specula {

using WarningHandler = std::function<void(std::string_view message)>;

// Replaces where warnings go; an empty handler restores stderr. Not thread-safe against
// a concurrent warn(): set it once, at start-up.
void setWarningHandler(WarningHandler handler);

// Reports one warning through the current handler.
void warn(std::string_view message);

} // namespace specula
