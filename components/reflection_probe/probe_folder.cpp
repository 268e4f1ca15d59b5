#include "probe_folder.h"

#include "engine/core/error.h"

#include <fstream>
#include <unistd.h>

namespace fs = std::filesystem;

namespace specula {

void writeProbeFolder(const std::string& dir,
                      const std::function<nlohmann::json(const fs::path& tmp)>& fill) {
    const fs::path target = fs::absolute(dir);
    const fs::path tmp = target.string() + ".tmp-" + std::to_string(::getpid());
    std::error_code ec;
    if (fs::exists(target, ec) && !fs::is_directory(target, ec))
        throw Error(dir, "", "exists and is not a folder; refusing to replace it");
    if (fs::is_directory(target, ec) && !fs::exists(target / "manifest.json", ec) &&
        !fs::is_empty(target, ec))
        throw Error(dir, "",
                    "is a folder without manifest.json (not a cooked probe); refusing "
                    "to replace it");
    fs::remove_all(tmp, ec);
    fs::create_directories(tmp);
    try {
        const nlohmann::json manifest = fill(tmp);
        std::ofstream out(tmp / "manifest.json");
        out << manifest.dump(2) << "\n";
        out.close();
        if (!out) throw Error((tmp / "manifest.json").string(), "", "write failed");

        // Swap the finished folder in; the old one is removed only after the rename worked.
        const fs::path old = target.string() + ".old-" + std::to_string(::getpid());
        const bool hadOld = fs::exists(target);
        if (hadOld) fs::rename(target, old);
        try {
            fs::rename(tmp, target);
        } catch (...) {
            if (hadOld) fs::rename(old, target);
            throw;
        }
        if (hadOld) fs::remove_all(old, ec);
    } catch (...) {
        fs::remove_all(tmp, ec);
        throw;
    }
}

} // namespace specula
