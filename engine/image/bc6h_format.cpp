#include "bc6h_format.h"

#include <cstdlib>

namespace specula::bc6h_detail {

const std::array<ModeHeader, 14>& modeHeaders() {
    static const std::array<ModeHeader, 14> headers = [] {
        std::array<ModeHeader, 14> h{};
        for (std::size_t m = 0; m < kModes.size(); ++m) {
            ModeHeader& out = h[m];
            for (const char* p = kModes[m].layout; *p;) {
                if (*p == ' ') {
                    ++p;
                    continue;
                }
                const int channel = p[0] == 'r' ? 0 : p[0] == 'g' ? 1 : 2;
                const int field = (p[1] - '0') * 3 + channel;
                char* end = nullptr;
                const long hi = std::strtol(p + 3, &end, 10);
                long lo = hi;
                if (*end == ':') lo = std::strtol(end + 1, &end, 10);
                // The lowest position holds the range's right-hand bit.
                const long step = lo <= hi ? 1 : -1;
                for (long b = lo;; b += step) {
                    out.refs[std::size_t(out.count++)] = {std::uint8_t(field), std::uint8_t(b)};
                    if (b == hi) break;
                }
                p = end + 1; // past ']'
            }
            if (kModes[m].regions == 2)
                for (std::uint8_t b = 0; b < 5; ++b)
                    out.refs[std::size_t(out.count++)] = {kPartitionField, b};
        }
        return h;
    }();
    return headers;
}

} // namespace specula::bc6h_detail
