#pragma once
// The bench's rows, made from the flavours' method tables: one per (method, accuracy
// parameter). A distance method is swept over d_e when its table row says its accuracy
// depends on it; the light field has one row per cooked light field.
#include "components/reflection_probe/distance/distance_probe.h"
#include "components/reflection_probe/method_label.h"

#include <string>
#include <vector>

namespace specula {

enum class VariantKind {
    Probe,       // drawn by ReflectionProbeSystem with `probe`
    GroundTruth, // the Embree tracer itself
};

struct MethodVariant {
    std::string method; // "envmap", "bisection", ..., "lightfield", "groundtruth"
    std::string params; // "d_e=0.01", "-" when the method has none
    VariantKind kind = VariantKind::Probe;
    DistanceProbe distance; // the distance probe's settings (asset: the scene's manifest)
    int lightField = -1;    // >= 0: index of the light-field asset it uses (else distance)
    bool planned = false;   // uses the probe baked by the effect plan
};

struct BenchSweep {
    std::vector<float> tolerances = {0.1f, 0.03f, 0.01f, 0.003f}; // d_e, metres
    // One light-field row per cooked light field (its params, e.g. "num=16 res=64").
    std::vector<std::string> lightFields;
};

// The distance methods in table order (envmap first: every ratio is to it) with their d_e
// sweeps, the light fields, the ground truth last.
std::vector<MethodVariant> benchVariants(const BenchSweep& sweep);

// Every method the sandbox offers, from the flavours' method tables: the distance rows in
// table order, then the light field, then the PEM rows. Names walk's --method, the plot's colours
// and legend.
std::vector<MethodLabel> sandboxMethods();

// The plot and the tables name a sweep by its method: rows of one method form a line.
std::string formatTolerance(float de);

} // namespace specula
