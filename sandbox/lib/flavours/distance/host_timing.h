#pragma once
// specula-sandbox host: the host path against Specula's own, on one view. The same cooked
// distance probe drawn on the scene's reflectors twice in interleaved rounds: by the sandbox
// (ReflectionProbeSystem's reflector pass) and by a host's own program (the reflector meshes,
// the host's fragment shader after DistanceHostProbe::glslLibrary(), bindTo per draw, its own
// Schlick Fresnel), as examples/minimal draws. Both frames are compared, and their reflector
// passes timed with one clock (FrameRenderer::passMs's).
#include <iosfwd>
#include <string>
#include <vector>

namespace specula::sandbox {

struct HostTimingOptions {
    std::string scene, sky, out;
    std::string probe; // a cooked distance probe's manifest; empty: baked into OUT/probe
    int width = 1024, height = 768;
    int faceRes = 256;
    int rounds = 31; // interleaved rounds, one timed frame per path each
    bool progress = true;
};

struct HostTimingRow {
    std::string path; // "sandbox" or "host"
    int frames = 0;
    double q1Ms = 0.0, medianMs = 0.0, q3Ms = 0.0;
    double ratioToSandbox = 0.0; // median / the sandbox's median
};

struct HostTimingResult {
    std::vector<HostTimingRow> rows;
    std::string timer, renderer;
    double psnrToSandbox = 0.0; // the host frame against the sandbox's (+inf: identical)
    double maxDifference = 0.0;
    int reflectors = 0;
    // The two spreads overlap: at this many rounds the paths cannot be told apart.
    bool indistinguishable = false;
};

// Writes OUT/host.csv and OUT/host.png (the sandbox's frame, the host's, their difference x 10).
// Throws Error naming the file on bad input (no reflector, a probe that is not distance).
HostTimingResult runHostTiming(const HostTimingOptions& options, std::ostream& log);

} // namespace specula::sandbox

namespace specula::cli {
class ToolCli;
}

namespace specula::sandbox {

void addHostCommand(cli::ToolCli& tool); // host_timing_cli.cpp

} // namespace specula::sandbox
