#pragma once
// A small command-line flag reader shared by the tools: `--name VALUE`, `--name=VALUE` and
// boolean `--name`; whatever is left must be positional, so a misspelt flag is an error and
// never silently ignored.
#include <glm/vec3.hpp>

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace specula {

// A wrong command line (exit status 2), as opposed to bad input data (Error, exit 1).
struct UsageError {
    std::string message;
};

class Flags {
public:
    explicit Flags(std::span<const std::string> args) : args_(args.begin(), args.end()) {}

    // Removes and returns the value of --name; throws UsageError when the value is missing.
    std::optional<std::string> value(const std::string& name);
    // Removes --name and reports whether it was there.
    bool flag(const std::string& name);
    // Every value of a repeatable --name, in order.
    std::vector<std::string> values(const std::string& name);

    int intValue(const std::string& name, int fallback, int lo, int hi);
    float floatValue(const std::string& name, float fallback, float lo, float hi);
    std::optional<glm::vec3> vec3Value(const std::string& name);

    // What is left; throws UsageError naming the first unknown flag.
    std::vector<std::string> positionals() const;

private:
    std::vector<std::string> args_;
};

// Strict number parsing for flags: the whole string must be a finite number in [lo, hi].
float parseFloat(const std::string& flag, const std::string& text, float lo, float hi);
int parseInt(const std::string& flag, const std::string& text, int lo, int hi);

} // namespace specula
