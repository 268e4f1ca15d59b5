#include "assetcooker/lib/cli/bake_args.h"

#include "engine/core/error.h"

#include <algorithm>

namespace specula::cook {

CookOptions checkedCookOptions(const BakeArgs& a) {
    CookOptions o;
    o.scene = a.scene;
    o.out = a.out;
    if (a.sky) o.sky = *a.sky;
    if (a.probes.size() == 1) o.probeCentre = cli::parseVec3(a.probes.front());
    o.flavour = a.flags.settings(a.flavour, a.scene);
    return o;
}

int checkedShardRows(const BakeArgs& a, const CookOptions& options) {
    if (!a.shardRows) return 0;
    if (a.flavour != "lightfield")
        throw UsageError("--shard-rows",
                         "applies to --flavour lightfield (a " + a.flavour +
                             " probe is one shard: its bake is a GPU raster, not rays)");
    const int cameras = std::get<LightFieldCookSettings>(options.flavour).cameras;
    if (*a.shardRows < 1 || *a.shardRows > cameras)
        throw UsageError("--shard-rows", "expected 1 .. NUM = --cameras " +
                                             std::to_string(cameras) + ", got " +
                                             std::to_string(*a.shardRows));
    return *a.shardRows;
}

CLI::Option* addShardRowsOption(CLI::App* sub, std::optional<int>& rows) {
    return sub->add_option(
        "--shard-rows", rows,
        "light field: split each probe into part shards of N camera rows of one slab\n"
        "(6 x ceil(NUM / N) parts a probe, then the probe's assembly); 1 .. NUM, default NUM\n"
        "(one part a slab). The probe's bytes do not depend on it");
}

bool isLevel(const BakeArgs& a, const ProbeScene& scene) {
    return a.probeList || a.probes.size() > 1 || scene.markup.probes.size() > 1;
}

LevelCookOptions levelCookOptions(const BakeArgs& a, const CookOptions& options,
                                  const ProbeScene& scene) {
    if (a.flavour == "pem")
        throw UsageError("--flavour", "pem bakes one probe's camera path, not a level of " +
                                          std::to_string(std::max<std::size_t>(
                                              a.probes.size(), scene.markup.probes.size())) +
                                          " probes: give one --probe");
    LevelCookOptions level;
    level.cook = options;
    level.cook.probeCentre.reset();
    for (const std::string& p : a.probes)
        level.sources.positions.push_back(cli::parseVec3(p));
    if (a.probeList) level.sources.file = *a.probeList;
    return level;
}

LevelCookOptions shardedCookOptions(const BakeArgs& a, const CookOptions& options,
                                    const ProbeScene& scene, const char* flag) {
    if (a.flavour == "pem" && !isLevel(a, scene)) {
        LevelCookOptions pem;
        pem.cook = options;
        return pem;
    }
    if (!isLevel(a, scene))
        throw UsageError(flag, a.scene + " has one probe: `specula-cook bake` bakes it (shards "
                                         "split a level: several probes, --probe twice or "
                                         "--probes FILE; or a PEM's samples: --flavour pem)");
    return levelCookOptions(a, options, scene);
}

void addBakeOptions(cli::ToolCli& tool, CLI::App* sub, BakeArgs& a) {
    sub->add_option("SCENE", a.scene, "the glTF/GLB scene")->required();
    sub->add_option("--out", a.out, "output folder (replaced atomically; never half-written)")
        ->required()
        ->check(cli::nonEmpty("a folder"));
    a.flavour = cookFlavourNames().front();
    sub->add_option("--flavour", a.flavour, "probe flavour")
        ->check(CLI::IsMember(cookFlavourNames()));
    sub->add_option("--probe", a.probes,
                    "probe centre in world space (overrides the markup's); repeat it for a "
                    "level of several probes")
        ->check(cli::vec3Text());
    sub->add_option("--probes", a.probeList,
                    "a probe list (JSON: {\"probes\": [{\"name\", \"position\", \"proxy\", "
                    "\"influence\", \"blend_distance\", \"priority\", \"cell_size\"}]}): "
                    "bakes a level")
        ->check(CLI::ExistingFile);
    tool.allowEmpty(
        sub->add_option("--sky", a.sky,
                        "equirectangular panorama for the distant environment (default and '': "
                        "black)"));

    a.flags.add(tool, sub);
    // Library code names the fields it read; these are the flags that set them (the
    // flavours' own settings map themselves).
    tool.mapField("centre", "--probe");
    tool.mapField("cell.size", "--cell-size");
    tool.mapField("image_size", "--image-size");
}

} // namespace specula::cook
