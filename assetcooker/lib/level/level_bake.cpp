#include "assetcooker/lib/level/level_bake.h"

#include "assetcooker/lib/bake/cook_settings_json.h"

#include "components/reflection_probe/manifest_fields.h"
#include "components/reflection_probe/writer/probe_folder.h"
#include "engine/core/error.h"
#include "engine/core/progress.h"
#include "engine/raytrace/embree_scene.h"
#include "engine/scene/components.h"
#include "engine/scene/mesh_bounds.h"

#include <algorithm>
#include <chrono>
#include <exception>
#include <filesystem>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

#include <tbb/parallel_for.h>

namespace specula {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

std::string folderNameFor(const std::string& name) {
    std::string out;
    for (char c : name)
        out += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '_';
    return out.empty() ? "probe" : out;
}

// The level folder may be written when it is missing, empty, or holds a level index.
std::optional<LevelIndex> previousLevel(const std::string& dir, std::vector<std::string>& notes) {
    std::error_code ec;
    if (!fs::exists(dir, ec)) return std::nullopt;
    if (!fs::is_directory(dir, ec)) throw Error(dir, "", "exists and is not a folder");
    const fs::path index = fs::path(dir) / "level.json";
    if (!fs::exists(index, ec)) {
        // The shard store (shard_bake.h) is the level's own.
        if (std::ranges::any_of(fs::directory_iterator(dir, ec), [](const fs::directory_entry& f) {
                return f.path().filename() != ".shards";
            }))
            throw Error(dir, "",
                        "holds files but no level.json: a level is written only into a new, "
                        "empty or level folder");
        return std::nullopt;
    }
    try {
        return readLevelIndex(index.string());
    } catch (const Error& e) {
        notes.push_back(std::string(e.what()) + ": every probe is re-baked");
        return LevelIndex{};
    }
}

// Every {"file", "checksum"} a manifest lists, at any depth (layers, sky, slabs, glossy
// levels): file -> checksum ("" when it states none). Depth-bounded like the manifest readers.
void listedFiles(const nlohmann::json& j, std::map<std::string, std::string>& files,
                 int depth = 0) {
    if (depth > 16) return;
    if (j.is_object()) {
        const auto file = j.find("file");
        if (file != j.end() && file->is_string()) {
            const auto sum = j.find("checksum");
            files[file->get<std::string>()] =
                sum != j.end() && sum->is_string() ? sum->get<std::string>() : "";
        }
        for (const auto& [key, value] : j.items())
            if (key != "file") listedFiles(value, files, depth + 1);
    } else if (j.is_array()) {
        for (const nlohmann::json& v : j)
            listedFiles(v, files, depth + 1);
    }
}

// Why the files a probe folder's manifest lists are not what it says ("" when they are): the
// first one missing or whose bytes differ from its checksum.
std::string folderFilesReason(const fs::path& folder) {
    const std::string manifest = (folder / "manifest.json").string();
    std::map<std::string, std::string> files;
    try {
        listedFiles(parseManifestJson(readManifestText(manifest), manifest), files);
    } catch (const Error& e) {
        return std::string("asset unreadable (") + e.what() + ")";
    }
    std::error_code ec;
    for (const auto& [file, sum] : files) {
        const fs::path path = folder / file;
        if (file.find("..") != std::string::npos || !fs::is_regular_file(path, ec))
            return "file " + file + " missing";
        try {
            if (!sum.empty() && fileChecksum(path.string()) != sum)
                return "file " + file + " altered on disk";
        } catch (const Error& e) {
            return "file " + file + " unreadable (" + e.what() + ")";
        }
    }
    return "";
}

std::string staleReason(const std::optional<LevelIndex>& previous, const fs::path& dir,
                        const std::string& folder, const ProbeVolume& v,
                        const ProbeInputs& inputs) {
    const LevelProbeEntry* old = nullptr;
    if (previous)
        for (const LevelProbeEntry& e : previous->probes)
            if (e.volume.name == v.name) old = &e;
    if (!old) return "new";
    const fs::path manifest = dir / folder / "manifest.json";
    std::error_code ec;
    if (old->folder != folder || !fs::is_regular_file(manifest, ec)) return "asset missing";
    if (fileChecksum(manifest.string()) != old->manifestChecksum) return "asset altered on disk";
    // The manifest alone proves nothing of the files it lists: each is checked too.
    if (std::string why = folderFilesReason(dir / folder); !why.empty()) return why;
    std::vector<std::string> why;
    if (old->inputs.geometry != inputs.geometry) why.push_back("geometry changed");
    if (old->inputs.options != inputs.options) why.push_back("options changed");
    if (old->inputs.sky != inputs.sky) why.push_back("sky changed");
    std::string joined;
    for (const std::string& w : why)
        joined += (joined.empty() ? "" : ", ") + w;
    return joined;
}

} // namespace

std::vector<std::string> levelStaleness(ProbeScene& scene, const LevelIndex& index,
                                        const std::string& indexPath, bool compareSky) {
    const EmbreeScene env(scene.registry,
                          [&](ecs::Entity e) { return scene.markup.mirrorEntities.count(e) == 0; });
    std::vector<std::string> lines;
    for (std::size_t i = 0; i < index.probes.size(); ++i) {
        const LevelProbeEntry& p = index.probes[i];
        const ProbeInputs now = levelProbeInputs(scene, env, p.volume, "");
        const std::string field = indexPath + ": probes[" + std::to_string(i) + "].inputs.";
        if (now.geometry != p.inputs.geometry)
            lines.push_back(field + "geometry: probe '" + p.volume.name + "' was baked from " +
                            index.source +
                            " with other meshes, materials or reflectors within its reach than " +
                            scene.path + " has");
        if (compareSky && now.sky != p.inputs.sky)
            lines.push_back(field + "sky: probe '" + p.volume.name + "' was baked under sky " +
                            p.inputs.sky + ", the scene's sky is " + now.sky);
    }
    return lines;
}

LevelCookResult cookLevel(const LevelCookOptions& options, std::ostream* log) {
    ProbeScene scene(options.cook.scene, options.cook.sky);
    return cookLevel(scene, options, log);
}

LevelPlan planLevel(ProbeScene& scene, const LevelCookOptions& options, std::ostream* log) {
    if (std::holds_alternative<PemCookSettings>(options.cook.flavour))
        throw Error(scene.path, "flavour",
                    "a level bakes distance or lightfield probes; a PEM follows one camera "
                    "path: bake it per probe with one --probe");
    const fs::path dir = options.cook.out;
    LevelPlan plan;
    plan.previous = previousLevel(dir.string(), plan.warnings);
    GatheredProbes gathered = gatherLevelProbes(scene, options.sources);
    plan.warnings.insert(plan.warnings.end(), gathered.warnings.begin(), gathered.warnings.end());
    if (log)
        for (const std::string& w : plan.warnings)
            *log << "warning: " << w << '\n';
    plan.index.source = scene.path;
    plan.index.flavour = std::visit(
        [](const auto& s) -> std::string {
            using S = std::decay_t<decltype(s)>;
            return std::is_same_v<S, LightFieldCookSettings> ? "lightfield" : "distance";
        },
        options.cook.flavour);
    std::set<std::string> folders;
    const EmbreeScene env(scene.registry,
                          [&](ecs::Entity e) { return scene.markup.mirrorEntities.count(e) == 0; });
    for (const ProbeVolume& v : gathered.probes) {
        LevelProbeEntry e;
        e.volume = v;
        e.folder = folderNameFor(v.name);
        for (int k = 2; folders.count(e.folder); ++k)
            e.folder = folderNameFor(v.name) + "_" + std::to_string(k);
        folders.insert(e.folder);
        // Every setting of the flavour, as the shard list carries them (cookSettingsToJson
        // names them all): changing any re-bakes.
        e.inputs = levelProbeInputs(scene, env, v, cookSettingsToJson(options.cook.flavour).dump());
        std::string reason = staleReason(plan.previous, dir, e.folder, v, e.inputs);
        if (reason.empty() && plan.previous)
            for (const LevelProbeEntry& old : plan.previous->probes)
                if (old.volume.name == v.name) e.manifestChecksum = old.manifestChecksum;
        plan.index.probes.push_back(std::move(e));
        plan.reasons.push_back(std::move(reason));
    }
    return plan;
}

CookOptions levelProbeCookOptions(const ProbeScene& scene, const LevelCookOptions& options,
                                  const LevelProbeEntry& entry, const std::string& out) {
    CookOptions o = options.cook;
    o.scene = scene.path;
    o.out = out;
    o.probeCentre = entry.volume.position;
    o.cellSize = entry.volume.cellSize;
    o.proxy = entry.volume.proxy;
    // The plan reads this probe's own markup (none for a probe no node holds).
    o.markupProbe = -1;
    for (std::size_t m = 0; m < scene.markup.probes.size(); ++m)
        if (scene.markup.probes[m].node == entry.volume.name) o.markupProbe = int(m);
    o.progress = false;
    o.progressHook = nullptr;
    return o;
}

void warnOfDroppedProbes(const LevelPlan& plan, const std::string& dir,
                         std::vector<std::string>& warnings, std::ostream* log) {
    if (!plan.previous) return;
    for (const LevelProbeEntry& old : plan.previous->probes)
        if (std::ranges::none_of(plan.index.probes, [&](const LevelProbeEntry& e) {
                return e.folder == old.folder;
            })) {
            warnings.push_back(
                "probe " + old.volume.name + " is no longer in the level: its folder " +
                (fs::path(dir) / old.folder).string() + " is left as it was (delete it by hand)");
            if (log) *log << "warning: " << warnings.back() << '\n';
        }
}

LevelCookResult cookLevel(ProbeScene& scene, const LevelCookOptions& options, std::ostream* log) {
    const auto start = Clock::now();
    const fs::path dir = options.cook.out;
    // What killed bakes of this level left (DIR/<probe>.tmp-PID): under the caller's lock.
    std::ostringstream dropped;
    removeStaleTemporariesIn(dir.string(), log ? *log : dropped);
    LevelPlan plan = planLevel(scene, options, log);
    LevelCookResult result;
    result.warnings = plan.warnings;
    fs::create_directories(dir);
    // The index as it stands: fresh probes keep their entries, stale ones their old entry
    // until re-baked (or none), so an interrupted bake leaves a true index behind.
    LevelIndex index = plan.index;
    index.probes.clear();
    std::vector<std::size_t> stale;
    for (std::size_t i = 0; i < plan.index.probes.size(); ++i) {
        const LevelProbeEntry& e = plan.index.probes[i];
        result.probes.push_back({e.volume.name, e.folder, !plan.reasons[i].empty(),
                                 plan.reasons[i].empty() ? "up to date" : plan.reasons[i], 0.0});
        if (plan.reasons[i].empty()) {
            index.probes.push_back(e);
            continue;
        }
        stale.push_back(i);
        if (plan.previous)
            for (const LevelProbeEntry& old : plan.previous->probes)
                if (old.volume.name == e.volume.name && old.folder == e.folder)
                    index.probes.push_back(old);
    }

    std::optional<ProgressBar> bar;
    if (options.cook.progress && !stale.empty())
        bar.emplace("baking " + std::to_string(stale.size()) + " of " +
                    std::to_string(plan.index.probes.size()) + " probes of " +
                    fs::path(scene.path).filename().string());
    // The stale probes are the level's shards (shard_bake.h), run in-process with TBB; each
    // probe folder is replaced atomically and the index committed after each. A failing
    // probe does not stop the others: its error is thrown once all are done, the first in
    // the scene's order.
    std::mutex mutex;
    std::vector<double> fractions(stale.size(), 0.0);
    std::vector<std::exception_ptr> errors(stale.size());
    tbb::parallel_for(std::size_t(0), stale.size(), [&](std::size_t k) {
        LevelProbeEntry& entry = plan.index.probes[stale[k]];
        const auto probeStart = Clock::now();
        CookOptions o = levelProbeCookOptions(scene, options, entry, (dir / entry.folder).string());
        if (bar)
            o.progressHook = [&, k](double f) {
                const std::lock_guard lock(mutex);
                fractions[k] = f;
                double sum = 0;
                for (double x : fractions)
                    sum += x;
                bar->update(sum / double(stale.size()));
            };
        std::ostringstream probeLog;
        try {
            const CookResult r = cookProbe(scene, o, log ? &probeLog : nullptr);
            const std::lock_guard lock(mutex);
            entry.manifestChecksum = fileChecksum(r.manifest);
            result.probes[stale[k]].seconds =
                std::chrono::duration<double>(Clock::now() - probeStart).count();
            // Replace this probe's entry (or add it) and commit the index now.
            std::erase_if(index.probes, [&](const LevelProbeEntry& e) {
                return e.volume.name == entry.volume.name;
            });
            index.probes.push_back(entry);
            writeLevelIndex(index, (dir / "level.json").string());
        } catch (...) {
            errors[k] = std::current_exception();
        }
        const std::lock_guard lock(mutex);
        if (log) *log << probeLog.str();
    });
    bar.reset();
    for (const std::exception_ptr& e : errors)
        if (e) std::rethrow_exception(e);
    // The final index lists the probes in the scene's order.
    writeLevelIndex(plan.index, (dir / "level.json").string());
    warnOfDroppedProbes(plan, dir.string(), result.warnings, log);
    if (log) {
        for (const LevelProbeOutcome& p : result.probes) {
            *log << "probe " << p.name << ": ";
            if (p.baked)
                *log << "baked in " << p.seconds << " s (" << p.reason << ")\n";
            else
                *log << "up to date\n";
        }
    }
    result.index = (dir / "level.json").string();
    result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return result;
}

} // namespace specula
