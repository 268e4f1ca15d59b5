#pragma once
// A file the user named for a tool's output (farm --csv FILE, ...): a regular file (or a new
// one) is written atomically (writeFileAtomically: checked writes and close, then a rename);
// anything else the path already names, such as /dev/stdout or a pipe, is written in place,
// every write() and the close() checked, for a rename would replace the device itself. A full
// disk, a size limit or a closed reader is an Error naming the file, never a silent
// truncation.
#include <string>
#include <string_view>

namespace specula {

void writeOutputFile(const std::string& path, std::string_view bytes);

} // namespace specula
