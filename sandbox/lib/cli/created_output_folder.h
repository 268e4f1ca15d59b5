#pragma once
// A walk, bench or level run that fails leaves no output folder it created: unless kept, the
// guard removes the folders --out made (create_directories may make several) on the way out,
// provided they hold nothing but the sandbox's own partial outputs.
#include <filesystem>
#include <string>

namespace specula::sandbox {

// What walk, bench and level write into --out, partial outputs and temporaries included.
bool isOwnOutput(const std::string& name);

class CreatedOutputFolder {
public:
    explicit CreatedOutputFolder(std::string dir);
    CreatedOutputFolder(const CreatedOutputFolder&) = delete;
    CreatedOutputFolder& operator=(const CreatedOutputFolder&) = delete;
    void keep() { created_.clear(); }
    ~CreatedOutputFolder();

private:
    std::string dir_;
    std::filesystem::path created_;
};

} // namespace specula::sandbox
