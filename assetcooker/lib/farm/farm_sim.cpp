#include "assetcooker/lib/farm/farm_sim.h"

#include "assetcooker/lib/farm/shard_bake.h"
#include "assetcooker/lib/os/output_file.h"
#include "components/reflection_probe/manifest_fields.h"
#include "engine/core/error.h"
#include "engine/image/plot_canvas.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <numeric>
#include <queue>
#include <sstream>

namespace specula {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// A specula-shard-time file's fields; throws Error naming the file and the field.
struct RecordedTime {
    double seconds = 0;
    std::string by = "bake-shard"; // who recorded it: "bake-shard" (when not said), "merge"
    // merge.time.json: the part spent computing dependents; -1 in files older than the field
    double assemblySeconds = -1;
};

double nonNegative(const json& doc, const std::string& file, const char* field) {
    if (!doc[field].is_number() || !std::isfinite(doc[field].get<double>()) ||
        doc[field].get<double>() < 0)
        throw Error(file, field, "expected a number of seconds >= 0");
    return doc[field].get<double>();
}

RecordedTime recordedTime(const std::string& file) {
    const json doc = parseManifestJson(readManifestText(file), file);
    if (!doc.is_object() || doc.value("format", "") != "specula-shard-time")
        throw Error(file, "format", "expected a specula-shard-time file");
    if (!doc.contains("seconds")) throw Error(file, "seconds", "expected a number of seconds >= 0");
    RecordedTime t;
    t.seconds = nonNegative(doc, file, "seconds");
    if (doc.contains("by")) {
        if (!doc["by"].is_string()) throw Error(file, "by", "expected \"bake-shard\" or \"merge\"");
        t.by = doc["by"].get<std::string>();
    }
    if (doc.contains("assembly_seconds"))
        t.assemblySeconds = nonNegative(doc, file, "assembly_seconds");
    return t;
}

double sumSeconds(const std::vector<FarmShardTime>& shards) {
    double t = 0;
    for (const FarmShardTime& s : shards)
        t += s.seconds;
    return t;
}

std::vector<double> secondsOf(const std::vector<FarmShardTime>& shards) {
    std::vector<double> seconds;
    for (const FarmShardTime& s : shards)
        seconds.push_back(s.seconds);
    return seconds;
}

} // namespace

double FarmTimes::total() const {
    return sumSeconds(shards) + sumSeconds(dependents);
}

FarmTimes readFarmTimes(const std::string& dir) {
    const ShardList list = readShardList(dir);
    FarmTimes times;
    times.dir = dir;
    std::string missing;
    std::size_t missingCount = 0;
    bool dependentMissing = false;
    double assembledByMerge = 0; // dependents' seconds recorded by the merge that computed them
    std::error_code ec;
    for (std::size_t i = 0; i < list.shards.size(); ++i) {
        const bool leaf = shardDependencies(list, int(i)).empty();
        const std::string file = shardTimePath(dir, list.shards[i]);
        if (!fs::is_regular_file(file, ec)) {
            missing += (missing.empty() ? "" : ", ") + std::to_string(i) + " (" +
                       shardLabel(list, int(i)) + ", " + file + ")";
            ++missingCount;
            dependentMissing = dependentMissing || !leaf;
            continue;
        }
        const RecordedTime t = recordedTime(file);
        const FarmShardTime shard{int(i), shardLabel(list, int(i)), t.seconds};
        (leaf ? times.shards : times.dependents).push_back(shard);
        if (!leaf && t.by == "merge") assembledByMerge += t.seconds;
    }
    if (missingCount > 0)
        throw Error(shardListPath(dir), "shards",
                    std::to_string(missingCount) + " of " + std::to_string(list.shards.size()) +
                        " shards have no recorded time: " + missing +
                        "; run specula-cook bake-shard for each" +
                        (dependentMissing ? " (or merge, which computes and records the "
                                            "dependent shards it lacks)"
                                          : "") +
                        " (a shard baked before times were recorded: delete its files in the "
                        "store and bake it again)");
    if (fs::is_regular_file(mergeTimePath(dir), ec)) {
        const RecordedTime merge = recordedTime(mergeTimePath(dir));
        // Files written before merge recorded its assembly: the dependents it computed (their
        // sum bounds the parallel assembly's wall from above).
        const double assembly =
            merge.assemblySeconds >= 0 ? merge.assemblySeconds : assembledByMerge;
        times.mergeSeconds = std::max(0.0, merge.seconds - assembly);
        times.mergeRecorded = true;
    }
    return times;
}

double arrayWall(std::vector<double> seconds, int nodes, double overhead) {
    std::sort(seconds.begin(), seconds.end(), std::greater<>());
    // Each node's finish time; the shard goes to the node that is free first.
    std::priority_queue<double, std::vector<double>, std::greater<>> free;
    for (int n = 0; n < std::max(1, nodes); ++n)
        free.push(0.0);
    double last = 0;
    for (double t : seconds) {
        const double finish = free.top() + overhead + t;
        free.pop();
        free.push(finish);
        last = std::max(last, finish);
    }
    return last;
}

double farmWall(std::vector<double> leaves, int nodes, double overhead, double mergeSeconds,
                std::vector<double> dependents) {
    return arrayWall(std::move(leaves), nodes, overhead) +
           arrayWall(std::move(dependents), nodes, overhead) + overhead + mergeSeconds;
}

std::vector<FarmRow> simulateFarm(const FarmTimes& times, const std::vector<int>& nodes,
                                  double overhead) {
    std::vector<FarmRow> rows;
    for (int n : nodes) {
        FarmRow r;
        r.nodes = n;
        r.wall = farmWall(secondsOf(times.shards), n, overhead, times.mergeSeconds,
                          secondsOf(times.dependents));
        r.ideal = times.total() / n;
        r.ratio = r.ideal > 0 ? r.wall / r.ideal : 0.0;
        rows.push_back(r);
    }
    return rows;
}

void writeFarmCsv(const std::string& file, const std::vector<FarmLevel>& levels) {
    std::ostringstream out;
    out << "level,shards,dependents,total_s,merge_s,nodes,wall_s,ideal_s,ratio\n";
    for (const FarmLevel& l : levels)
        for (const FarmRow& r : l.rows)
            out << l.label << ',' << l.times.shards.size() << ',' << l.times.dependents.size()
                << ',' << l.times.total() << ',' << l.times.mergeSeconds << ',' << r.nodes << ','
                << r.wall << ',' << r.ideal << ',' << r.ratio << '\n';
    writeOutputFile(file, out.str()); // every byte checked: a full disk is an Error
}

Image farmPlot(const std::vector<FarmLevel>& levels, double overhead, int w, int h) {
    using OIIO::ImageBufAlgo::TextAlignX;
    PlotCanvas cv(w, h);
    const PlotColour axis{0.8f, 0.8f, 0.8f}, grid{0.07f, 0.07f, 0.08f}, white{1.f, 1.f, 1.f};
    const PlotColour palette[] = {{0.95f, 0.55f, 0.15f}, {0.30f, 0.65f, 0.95f},
                                  {0.45f, 0.85f, 0.40f}, {0.90f, 0.35f, 0.55f},
                                  {0.75f, 0.60f, 0.95f}, {0.95f, 0.85f, 0.30f}};
    const int left = 72, right = w - 24, top = 58, bottom = h - 56;
    double n0 = 1, n1 = 2, s0 = 0, s1 = 0;
    bool any = false;
    for (const FarmLevel& l : levels)
        for (const FarmRow& r : l.rows)
            for (double s : {r.wall, r.ideal})
                if (s > 0) {
                    n0 = any ? std::min(n0, double(r.nodes)) : r.nodes;
                    n1 = any ? std::max(n1, double(r.nodes)) : std::max(2.0, double(r.nodes));
                    s0 = any ? std::min(s0, s) : s, s1 = any ? std::max(s1, s) : s;
                    any = true;
                }
    const double lx0 = std::floor(std::log2(n0)), lx1 = std::max(lx0 + 1, std::ceil(std::log2(n1)));
    const double ly0 = any ? std::floor(std::log2(s0)) : 0.0;
    const double ly1 = any ? std::max(ly0 + 1, std::ceil(std::log2(s1))) : 1.0;
    auto X = [&](double n) {
        return int(left + (std::log2(n) - lx0) / (lx1 - lx0) * (right - left));
    };
    auto Y = [&](double s) {
        return int(bottom - (std::log2(s) - ly0) / (ly1 - ly0) * (bottom - top));
    };
    for (double l = lx0; l <= lx1 + 1e-9; l += 1) {
        const int x = X(std::exp2(l));
        cv.line(x, top, x, bottom, grid);
        cv.text(x, bottom + 20, plotNumber("%.0f", std::exp2(l)), 13, axis, TextAlignX::Center);
    }
    for (double l = ly0; l <= ly1 + 1e-9; l += 1) {
        const int y = Y(std::exp2(l));
        cv.line(left, y, right, y, grid);
        // Whole seconds from 1 s up (%.3g would print 1024 as 1.02e+03).
        cv.text(left - 8, y + 5, plotNumber(l >= 0 ? "%.0f" : "%.3g", std::exp2(l)), 13, axis,
                TextAlignX::Right);
    }
    cv.box(left, top, right, bottom, axis, false);
    cv.text((left + right) / 2, h - 14, "nodes (log scale)", 14, axis, TextAlignX::Center);
    cv.text(14, top - 10, "wall seconds (log scale)", 13, axis);
    cv.text((left + right) / 2, 24,
            "simulated farm: predicted wall (solid) and ideal total/N (dashed), " +
                plotNumber("%.2g", overhead) + " s a shard",
            15, white, TextAlignX::Center);
    int ly = top + 20;
    for (std::size_t i = 0; i < levels.size(); ++i) {
        const PlotColour& c = palette[i % std::size(palette)];
        const std::vector<FarmRow>& rows = levels[i].rows;
        for (std::size_t k = 0; k < rows.size(); ++k) {
            const FarmRow& r = rows[k];
            if (r.wall <= 0 || r.ideal <= 0) continue;
            cv.box(X(r.nodes) - 4, Y(r.wall) - 4, X(r.nodes) + 4, Y(r.wall) + 4, c, true);
            if (k == 0 || rows[k - 1].wall <= 0 || rows[k - 1].ideal <= 0) continue;
            const FarmRow& q = rows[k - 1];
            cv.thickLine(X(q.nodes), Y(q.wall), X(r.nodes), Y(r.wall), c);
            cv.dashed(X(q.nodes), Y(q.ideal), X(r.nodes), Y(r.ideal), c);
        }
        cv.box(right - 300, ly - 9, right - 288, ly + 1, c, true);
        cv.text(right - 282, ly, levels[i].label, 13, axis);
        ly += 18;
    }
    return cv.image();
}

} // namespace specula
