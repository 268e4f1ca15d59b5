#include "sandbox/lib/cli/created_output_folder.h"

#include "engine/core/file_write.h"

#include <regex>
#include <vector>

namespace specula::sandbox {

bool isOwnOutput(const std::string& name) {
    static const std::regex own(
        R"(((frame_\d+|contact_sheet|accuracy_vs_time|strip_.+|level_walk)\.png)"
        R"(|frames\.csv|summary\.csv|glossy\.csv|bench\.(csv|md))(\.tmp-\d+)?)"
        R"(|probes?(\.(tmp|old)-\d+)?|level)");
    return std::regex_match(name, own);
}

CreatedOutputFolder::CreatedOutputFolder(std::string dir)
    : dir_(std::move(dir)), created_(outermostMissingFolder(dir_)) {}

CreatedOutputFolder::~CreatedOutputFolder() {
    namespace fs = std::filesystem;
    if (created_.empty()) return;
    try {
        const std::vector<fs::directory_entry> entries(fs::directory_iterator(dir_),
                                                       fs::directory_iterator{});
        for (const fs::directory_entry& e : entries)
            if (!isOwnOutput(e.path().filename().string())) return;
        for (const fs::directory_entry& e : entries)
            fs::remove_all(e.path());
        removeEmptyFoldersUpTo(dir_, created_);
    } catch (const std::exception&) {
        // Leaving a folder behind is the lesser harm; the run's own error is reported.
    }
}

} // namespace specula::sandbox
