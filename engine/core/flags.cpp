#include "flags.h"

#include <charconv>
#include <cmath>
#include <sstream>

namespace specula {

std::optional<std::string> Flags::value(const std::string& name) {
    std::optional<std::string> found;
    for (std::size_t i = 0; i < args_.size();) {
        const std::string& a = args_[i];
        if (a == "--") break;
        if (a == name) {
            if (i + 1 >= args_.size()) throw UsageError{name + " needs a value"};
            found = args_[i + 1];
            args_.erase(args_.begin() + long(i), args_.begin() + long(i) + 2);
        } else if (a.rfind(name + "=", 0) == 0) {
            found = a.substr(name.size() + 1);
            args_.erase(args_.begin() + long(i));
        } else {
            ++i;
        }
    }
    return found;
}

std::vector<std::string> Flags::values(const std::string& name) {
    std::vector<std::string> out;
    for (std::size_t i = 0; i < args_.size();) {
        const std::string& a = args_[i];
        if (a == "--") break;
        if (a == name) {
            if (i + 1 >= args_.size()) throw UsageError{name + " needs a value"};
            out.push_back(args_[i + 1]);
            args_.erase(args_.begin() + long(i), args_.begin() + long(i) + 2);
        } else if (a.rfind(name + "=", 0) == 0) {
            out.push_back(a.substr(name.size() + 1));
            args_.erase(args_.begin() + long(i));
        } else {
            ++i;
        }
    }
    return out;
}

bool Flags::flag(const std::string& name) {
    bool found = false;
    for (std::size_t i = 0; i < args_.size();) {
        if (args_[i] == "--") break;
        if (args_[i] == name) {
            found = true;
            args_.erase(args_.begin() + long(i));
        } else {
            ++i;
        }
    }
    return found;
}

float parseFloat(const std::string& flag, const std::string& text, float lo, float hi) {
    float v = 0.f;
    const char* end = text.data() + text.size();
    auto [p, ec] = std::from_chars(text.data(), end, v);
    if (ec != std::errc() || p != end || !std::isfinite(v) || v < lo || v > hi) {
        std::ostringstream s;
        s << flag << ": expected a number in [" << lo << ", " << hi << "], got '" << text << "'";
        throw UsageError{s.str()};
    }
    return v;
}

int parseInt(const std::string& flag, const std::string& text, int lo, int hi) {
    int v = 0;
    const char* end = text.data() + text.size();
    auto [p, ec] = std::from_chars(text.data(), end, v);
    if (ec != std::errc() || p != end || v < lo || v > hi)
        throw UsageError{flag + ": expected an integer in [" + std::to_string(lo) + ", " +
                         std::to_string(hi) + "], got '" + text + "'"};
    return v;
}

int Flags::intValue(const std::string& name, int fallback, int lo, int hi) {
    const auto v = value(name);
    return v ? parseInt(name, *v, lo, hi) : fallback;
}

float Flags::floatValue(const std::string& name, float fallback, float lo, float hi) {
    const auto v = value(name);
    return v ? parseFloat(name, *v, lo, hi) : fallback;
}

std::optional<glm::vec3> Flags::vec3Value(const std::string& name) {
    const auto v = value(name);
    if (!v) return std::nullopt;
    glm::vec3 out;
    std::size_t start = 0;
    for (int i = 0; i < 3; ++i) {
        const std::size_t comma = v->find(',', start);
        if ((i < 2) != (comma != std::string::npos))
            throw UsageError{name + ": expected x,y,z, got '" + *v + "'"};
        out[i] = parseFloat(name, v->substr(start, comma - start), -1e7f, 1e7f);
        start = comma + 1;
    }
    return out;
}

std::vector<std::string> Flags::positionals() const {
    std::vector<std::string> pos;
    bool done = false;
    for (const std::string& a : args_) {
        if (!done && a == "--") {
            done = true;
        } else if (!done && a.size() > 1 && a[0] == '-') {
            throw UsageError{"unknown option '" + a + "'"};
        } else {
            pos.push_back(a);
        }
    }
    return pos;
}

} // namespace specula
