#pragma once
// One error type for the whole project. User-facing errors name the file, the field
// and what was expected; internal invariants are asserts, not Errors.
#include <stdexcept>
#include <string>

namespace specula {

class Error : public std::runtime_error {
public:
    Error(std::string file, std::string field, const std::string& what)
        : std::runtime_error(compose(file, field, what)), file_(std::move(file)),
          field_(std::move(field)), message_(what) {}
    explicit Error(const std::string& what) : std::runtime_error(what), message_(what) {}

    const std::string& file() const { return file_; }
    const std::string& field() const { return field_; }
    // What was expected, without the file and the field (what() has all three): for a
    // caller that re-raises the error under another field or flag.
    const std::string& message() const { return message_; }

private:
    static std::string compose(const std::string& file, const std::string& field,
                               const std::string& what) {
        std::string s = file.empty() ? std::string() : file + ": ";
        if (!field.empty()) s += field + ": ";
        return s + what;
    }
    std::string file_, field_, message_;
};

// A wrong command line (exit status 2), as opposed to bad input data (exit 1). The field is
// the flag, when one is to blame. Tools catch it before Error, so it keeps its own status.
class UsageError : public Error {
public:
    using Error::Error;
    UsageError(std::string flag, const std::string& what) : Error("", std::move(flag), what) {}
};

// A run stopped on request (SIGINT/SIGTERM) before its commit point: nothing was replaced.
// Tools report it apart from bad input, with exit status 130 (128 + SIGINT).
class Cancelled : public Error {
public:
    using Error::Error;
};

} // namespace specula
