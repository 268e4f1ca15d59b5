#include "gltf_context.h"

#include <cctype>

namespace specula::gltf_internal {

std::string oneLine(const std::string& text) {
    std::string out;
    std::size_t start = 0;
    while (start <= text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        std::string part = text.substr(start, end - start);
        while (!part.empty() && std::isspace(static_cast<unsigned char>(part.back())))
            part.pop_back();
        std::size_t lead = 0;
        while (lead < part.size() && std::isspace(static_cast<unsigned char>(part[lead])))
            ++lead;
        part.erase(0, lead);
        if (!part.empty()) out += (out.empty() ? "" : "; ") + part;
        start = end + 1;
    }
    return out;
}

std::string idx(const char* what, std::size_t i) {
    return std::string(what) + "[" + std::to_string(i) + "]";
}

} // namespace specula::gltf_internal
