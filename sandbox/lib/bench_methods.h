#pragma once
// The bench's method table: one entry per (method, accuracy parameter) row. Adding a method
// is one entry in benchVariants(); the light field has one row per cooked light field.
#include "components/reflection_probe/reflection_probe.h"

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
    ReflectionProbe probe; // asset left empty: filled with the scene's manifest
    int lightField = -1;   // >= 0: index of the light-field asset it uses (else the distance probe)
    bool planned = false;  // uses the probe baked by the effect plan
};

struct BenchSweep {
    std::vector<float> tolerances = {0.1f, 0.03f, 0.01f, 0.003f}; // d_e, metres
    // One light-field row per cooked light field (its params, e.g. "num=16 res=64").
    std::vector<std::string> lightFields;
};

// Envmap first (every ratio is to it), then boxproj, the distance methods and their d_e
// sweeps, the light fields, the ground truth last.
std::vector<MethodVariant> benchVariants(const BenchSweep& sweep);

// Parses a method name for walk: the LookupMethod names (plus "lightfield" when built).
bool parseSandboxMethod(const std::string& s, LookupMethod& out);

// The plot and the tables name a sweep by its method: rows of one method form a line.
std::string formatTolerance(float de);

} // namespace specula
