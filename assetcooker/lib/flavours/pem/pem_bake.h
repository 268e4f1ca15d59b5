#pragma once
// The steps of a PEM bake (cookPemAsset, pem_samples.h), apart so that a one-machine bake and
// a sharded one (shard_pem.h: a trace shard per sample, an inference shard per sample) run
// the same code: the set-up every sample shares (the asset's centre, box and distance cube,
// the inference options, the reflectors' hull flags), one sample's trace, the local-layer
// decision from every sample's trace, one sample's inference.
#include "assetcooker/lib/flavours/pem/pem_samples.h"

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

namespace specula {

// The asset's local layer, decided from every sample's trace: "on", or "auto" where some
// off-hull ray of some sample meets its own reflector again; the sphere from every sample's
// off-hull points (all points when none is off the hull), by PemCookSettings::localSphere.
struct PemLocalDecision {
    bool local = false;
    int faceRes = 0; // the local cube's, set when local
    PemLocalSphere sphere;

    bool operator==(const PemLocalDecision&) const = default;
};
PemLocalDecision decidePemLocalLayer(const PemCookSettings& s,
                                     const std::vector<PemSamples>& traced);
// What the decision reads of one sample's trace: whether some off-hull ray meets its own
// reflector again, and the off-hull rays' points in trace order (a sharded bake keeps them
// apart so that each sample shard need not read every trace whole: pem_shard_files.h).
struct PemDecisionInputs {
    bool selfHits = false;
    std::vector<glm::vec3> offHull;
};
PemDecisionInputs pemDecisionInputs(const PemSamples& samples);
// The same decision from each sample's inputs; `allPoints` (every sample's points in order)
// is called only when no sample has an off-hull point.
PemLocalDecision decidePemLocalLayer(const PemCookSettings& s,
                                     const std::vector<PemDecisionInputs>& inputs,
                                     const std::function<std::vector<glm::vec3>()>& allPoints);
// Whether the decision reads the traces at all ("off" decides without them).
bool pemLocalDecisionNeedsTraces(const PemCookSettings& s);

class PemBake {
public:
    // What a step needs: the trace (the parameter state and the hull flags), the inference
    // (the distance cube at faceRes, the prior), or both.
    enum Needs { Trace = 1, Infer = 2, Both = 3 };

    // Validates the settings and the scene's reflectors; the asset's header (centre, box,
    // parameter, sizes, geometry and its distance cube when inferring) as cookPemAsset
    // writes it. `centre`: null for the markup's. The scene's reflectors are back where
    // they were authored when the bake goes.
    PemBake(ProbeScene& scene, const PemCookSettings& s, std::optional<glm::vec3> centre,
            Needs needs = Both);
    ~PemBake();
    PemBake(const PemBake&) = delete;
    PemBake& operator=(const PemBake&) = delete;

    // The asset without samples or local layer (see assemble).
    const PemAsset& header() const { return asset_; }
    // Sample k's parameter: k / samples on the walk's closed loops (t = 1 is t = 0 again),
    // k / (samples - 1) on the open camera path, whose both ends are samples.
    float parameter(int k) const { return pemSampleParameter(s_, k); }

    // Sample k's reflector rays (tracePemSamples at t = parameter(k), with the layer fields
    // unless localLayer is "off"). Throws Error naming the scene and "camera" (with the
    // sample) when the camera sees no reflector there.
    PemSamples trace(int k);
    // The samples at any t (the off-manifold measurement's half-way points); none where the
    // camera sees no reflector pixel there (a camera path that looks away). Other errors throw.
    std::optional<PemSamples> traceAt(float t);

    // Sample k's maps from its trace under the decision; `fit` (may be null) gets the
    // inference's figures (unseen texels, seconds).
    PemSampleMap infer(int k, const PemSamples& samples, const PemLocalDecision& d,
                       PemSampleFit* fit) const;

    // The asset: the header with the decision's layer and the sample maps, in order.
    PemAsset assemble(const PemLocalDecision& d, std::vector<PemSampleMap> samples) const;

private:
    class State;
    ProbeScene& scene_;
    PemCookSettings s_;
    PemAsset asset_;
    PemInferOptions infer_;
    std::vector<glm::vec3> captured_; // the prior (infer_.prior points here)
    std::unordered_map<ecs::Entity, PemHullFlags> hull_;
    PemSampleOptions options_;
    std::unique_ptr<State> state_; // tracing bakes only
};

} // namespace specula
