#pragma once
// This machine's name, as the writers of shared folders record it beside their process id (a
// lock file's holder, a temporary folder's owner): a process id means something only on the
// host that issued it.
#include <string>

namespace specula {

// gethostname's answer; "localhost" when it has none.
std::string hostName();

} // namespace specula
