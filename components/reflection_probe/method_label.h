#pragma once
// How a lookup method presents itself, the same in every flavour's method table: the name
// that selects it (CLI, manifests, bench rows), its plot colour and a one-line help. Tools
// list every flavour's labels; nothing keeps a parallel list of method names.
#include <array>

namespace specula {

struct MethodLabel {
    const char* name;
    std::array<float, 3> colour; // linear RGB, bright enough on the plot's dark grey
    const char* help;
};

} // namespace specula
