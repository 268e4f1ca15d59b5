#pragma once
// The cooking API: a scene and options in, a cooked probe folder out. `specula-cook bake`,
// the sandbox and the tests' fixtures all bake through it, so each flavour's
// plan -> bake -> write is written once. The folder is replaced atomically (probe_folder.h):
// a cancel requested (cancelRequested) before the commit leaves it as it was and throws
// Cancelled naming it.
#include "assetcooker/lib/flavours/distance/distance_cook_settings.h"
#include "assetcooker/lib/flavours/lightfield/lightfield_bake.h"
#include "assetcooker/lib/flavours/lightfield/lightfield_cook_settings.h"
#include "assetcooker/lib/flavours/pem/pem_samples.h"
#include "assetcooker/lib/plan/plan_budget.h"
#include "assetcooker/lib/scene/probe_setup.h"
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "components/reflection_probe/lightfield/lightfield_asset.h"
#include "engine/image/ggx_prefilter.h"

#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace specula {

// The cooker's flavours, one line each: the flavour is the settings' type, so one flavour's
// settings cannot reach another's. Each declares its settings once (visitSettings, in its
// folder's *_cook_settings.h), from which the bake's flags and the settings JSON derive.
using CookFlavour = std::variant<DistanceCookSettings, LightFieldCookSettings, PemCookSettings>;

// The flavours' names (kFlavour) in the variant's order, and as "a, b or c".
std::vector<std::string> cookFlavourNames();
std::string cookFlavourList();

// Calls f(defaults) with every flavour's default settings, in the variant's order.
template <class F> void forEachCookFlavour(F&& f) {
    [&]<std::size_t... I>(std::index_sequence<I...>) {
        (f(std::variant_alternative_t<I, CookFlavour>{}), ...);
    }
    (std::make_index_sequence<std::variant_size_v<CookFlavour>>{});
}

struct CookOptions {
    std::string scene;                    // .gltf/.glb; opened by cookProbe(options, log)
    std::string sky;                      // equirectangular panorama; empty: a black sky
    std::string out;                      // the cooked folder
    std::optional<glm::vec3> probeCentre; // default: the markup's (markupProbeCentre)
    // The cell reflectors move in (default: the markup's first probe's, markupCellSize) and
    // the proxy box of the distance flavour's box projection (default: the environment's
    // bounds); a level gives each probe its own.
    std::optional<float> cellSize;
    std::optional<Aabb> proxy;
    // The `specula_probe` node whose members the effect plan reads (index into the markup's
    // probes; a level gives each probe its own, -1 to one no node holds).
    int markupProbe = 0;
    CookFlavour flavour;
    bool progress = true; // a progress bar on the terminal while tracing
    // Called with the fraction done instead of drawing a bar (a level draws one bar for all).
    std::function<void(double)> progressHook;
    // Light field: the probe's blocks, already traced (a sharded bake's parts, shard_bake.h);
    // null: traced here. The folder written is the same, byte for byte.
    const std::vector<LightFieldRows>* lightFieldBlocks = nullptr;
};

struct CookResult {
    std::string manifest;   // out/manifest.json
    double bakeSeconds = 0; // planning and tracing; without opening the scene and writing
    // Distance, glossy: the GGX prefilter of the composite (not in bakeSeconds); 0 when none.
    double prefilterSeconds = 0;
    std::vector<std::string> warnings; // the probe placement's (also written to the log)
    std::variant<DistanceProbeAsset, LightFieldAsset, PemAsset> asset; // as written
    // Light field: the cell baked and the reflectors reaching outside it.
    glm::vec3 cellCentre{0.f};
    float cellSize = 0.f;
    std::vector<ReflectorOverhang> overhangs;
    // PEM: each sample's fit on and off the manifold, as the cooker measured it.
    std::vector<PemSampleFit> pemFits;
};

// What a probe cooked from `scene` with `settings` (cookSettingsToJson) at `centre` records
// as its "inputs" (sceneProbeInputs): the same whether one process or a farm's shards cook it.
ProbeInputs cookedProbeInputs(const ProbeScene& scene, const nlohmann::json& settings,
                              glm::vec3 centre);

// Repairs what killed bakes left beside options.out and refuses an out that may not be
// replaced (before any work), opens options.scene and options.sky, bakes and writes. On
// `log` (may be null): the repairs and the placement warnings. Throws Error naming the file
// and field on bad input, Cancelled when cancelled.
CookResult cookProbe(const CookOptions& options, std::ostream* log);
// The same on a scene already open (options.scene and options.sky are not read).
CookResult cookProbe(ProbeScene& scene, const CookOptions& options, std::ostream* log);

// The light-field baker's options cookProbe gives it (the cell from the settings, else the
// options', else the markup's; the sky); no progress, cancel, warnings or blocks.
LightFieldBakeOptions lightFieldBakeOptions(const ProbeScene& scene, const CookOptions& options,
                                            const LightFieldCookSettings& settings);

} // namespace specula
