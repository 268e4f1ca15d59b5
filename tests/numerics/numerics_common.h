#pragma once
// Shared by the numerics tests (docs/design.md §7): closed-form probes beyond the plain box room,
// the reference ("ideal") answer of every lookup method, and a GLSL harness that runs the
// real shared lookup (shaders/distance_lookup.glsl.h) over a list of rays on the GPU, so each
// hard case drives both the C++ twin and the shader through exactly the same inputs.
#include "components/reflection_probe/distance/distance_probe_cpu.h"
#include "components/reflection_probe/system/reflection_probe_system.h"
#include "engine/context/context.h"
#include "engine/gpu/gl_objects.h"
#include "engine/gpu/render_target.h"
#include "probe/analytic_probe.h"
#include "support/fullscreen_pass.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace specula::test {

inline bool finite3(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// The default closed-form room of the probe tests.
inline const AnalyticBox& room() {
    static const AnalyticBox box;
    return box;
}

// A box room without its ceiling: rays that leave through y = hi.y see nothing (d_inf, black
// radiance, no sky image so the sky answers black too).
struct OpenBox {
    AnalyticBox box;
    // Exact answer from x along unit d: the wall's radiance or black (sky).
    glm::vec3 trace(glm::vec3 x, glm::vec3 d) const {
        const float t = box.exit(x, d);
        const glm::vec3 p = x + t * d;
        if (p.y >= box.hi.y - 1e-5f * std::max(1.f, std::abs(box.hi.y))) return glm::vec3(0.f);
        return AnalyticBox::radianceAt(p);
    }
};

// A sphere alone in the dark: a small-solid-angle object whose silhouette meets d_inf.
struct Sphere {
    glm::vec3 c{2.2f, 0.3f, -0.4f};
    float r = 0.8f;
    std::optional<float> hit(glm::vec3 x, glm::vec3 d) const {
        const glm::vec3 o = x - c;
        const float b = glm::dot(o, d);
        const float q = glm::dot(o, o) - r * r;
        const float disc = b * b - q;
        if (disc < 0.f) return std::nullopt;
        const float s = std::sqrt(disc);
        const float t = q > 0.f ? -b - s : -b + s;
        if (t <= 0.f) return std::nullopt;
        return t;
    }
    glm::vec3 trace(glm::vec3 x, glm::vec3 d) const {
        const auto t = hit(x, d);
        return t ? AnalyticBox::radianceAt(x + *t * d) : glm::vec3(0.f);
    }
    // Distance from the sphere's outline as seen along the ray: > 0 outside (a miss),
    // < 0 inside (a hit); the ray's closest approach to the centre minus r.
    float margin(glm::vec3 x, glm::vec3 d) const {
        const glm::vec3 o = c - x;
        return glm::length(o - glm::dot(o, d) * d) - r;
    }
};

// A one-layer probe baked in closed form by `traceFromCentre(dir) -> (rgb, t or <0 miss)`.
template <typename F>
DistanceProbeAsset makeProbe(int n, float dInf, F traceFromCentre, glm::vec3 boxLo,
                             glm::vec3 boxHi) {
    DistanceProbeAsset a;
    a.faceRes = n;
    a.dInf = dInf;
    a.boxMin = boxLo;
    a.boxMax = boxHi;
    float maxD = 0.f;
    double sum = 0.0;
    long valid = 0;
    DistanceProbeLayer L;
    L.name = "closed-form";
    for (int f = 0; f < 6; ++f) {
        L.faces[std::size_t(f)] = Image(n, n, 4);
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const glm::vec2 uv((float(x) + 0.5f) / float(n), (float(y) + 0.5f) / float(n));
                const glm::vec3 d = glm::normalize(glsl::cubeFaceDirection(f, uv));
                glm::vec3 rgb;
                float t;
                traceFromCentre(d, rgb, t);
                float* p = L.faces[std::size_t(f)].at(x, y);
                p[0] = rgb.r, p[1] = rgb.g, p[2] = rgb.b;
                p[3] = t < 0.f ? dInf : t;
                if (t >= 0.f) {
                    maxD = std::max(maxD, t);
                    sum += t;
                    ++valid;
                }
            }
    }
    L.avgDistance = valid ? float(sum / double(valid)) : 0.f;
    L.boxMin = boxLo;
    L.boxMax = boxHi;
    L.solidAngle = 1.f;
    a.range = 0.5f * (maxD + 1.f) * 1.05f;
    a.layers.push_back(L);
    return a;
}

inline DistanceProbeAsset makeOpenBoxProbe(int n) {
    const OpenBox ob;
    return makeProbe(
        n, 1000.f,
        [&](glm::vec3 d, glm::vec3& rgb, float& t) {
            const float e = ob.box.exit(glm::vec3(0.f), d);
            const glm::vec3 p = e * d;
            if (p.y >= ob.box.hi.y - 1e-5f) {
                rgb = glm::vec3(0.f);
                t = -1.f;
            } else {
                rgb = AnalyticBox::radianceAt(p);
                t = e;
            }
        },
        ob.box.lo, ob.box.hi);
}

inline DistanceProbeAsset makeSphereProbe(int n, const Sphere& s) {
    DistanceProbeAsset a = makeProbe(
        n, 1000.f,
        [&](glm::vec3 d, glm::vec3& rgb, float& t) {
            const auto h = s.hit(glm::vec3(0.f), d);
            rgb = h ? AnalyticBox::radianceAt(*h * d) : glm::vec3(0.f);
            t = h ? *h : -1.f;
        },
        s.c - glm::vec3(s.r), s.c + glm::vec3(s.r));
    return a;
}

// Composite plus one object layer holding the same box: the layered mode's code path.
inline DistanceProbeAsset withObjectLayer(DistanceProbeAsset a, const char* method) {
    DistanceProbeLayer L = a.layers[0];
    L.name = "object";
    L.method = method;
    L.boxMin = a.boxMin;
    L.boxMax = a.boxMax;
    a.layers.push_back(L);
    return a;
}

inline const char* methodName(DistanceMethod m) {
    return toString(m);
}

// March last: the peer (Szirmay-Kalos et al. 2005) the searches are measured against.
inline constexpr DistanceMethod kAllMethods[] = {DistanceMethod::Envmap,    DistanceMethod::BoxProj,
                                                 DistanceMethod::Bisection, DistanceMethod::Secant,
                                                 DistanceMethod::AvgDist,   DistanceMethod::Layered,
                                                 DistanceMethod::March};

// Most distance fetches one layer's search may spend: the march steps and refinements for
// the march; for bisection and secant the first-crossing march (kBracketSteps) plus N, since
// on the composite they march to the first crossing before searching (issue 15; before it,
// N alone); the march's points are never spent on object layers, where N stays the bound.
// Secant's safeguard allows two steps for each halving of its bracket (secantIn): 2N.
inline int searchFetchCap(DistanceMethod m, const DistanceLookupConfig& c) {
    if (m == DistanceMethod::March) return glsl::kMarchSteps + glsl::kMarchRefineSteps;
    if (m == DistanceMethod::Secant) return glsl::kBracketSteps + 2 * c.params.maxSteps;
    if (m == DistanceMethod::Bisection) return glsl::kBracketSteps + c.params.maxSteps;
    return c.params.maxSteps;
}

inline DistanceLookupConfig configFor(const DistanceProbeAsset& a, DistanceMethod m,
                                      float de = 0.01f, float range = 0.f) {
    DistanceProbe p;
    p.method = m;
    p.layerMethod = DistanceMethod::Bisection;
    p.errorTolerance = de;
    p.range = range;
    return makeLookupConfig(p, a);
}

// What each method computes when nothing numerical goes wrong, for a box-room probe
// centred at the origin: envmap and avgdist look the room up from the centre along a
// direction (l-hat, or x + d-bar l-hat); box projection, bisection, secant, march and
// layered find the true reflection.
inline glm::vec3 idealBox(const AnalyticBox& box, DistanceMethod m, float avgDistance, glm::vec3 x,
                          glm::vec3 d) {
    switch (m) {
    case DistanceMethod::Envmap:
        return box.trace(glm::vec3(0.f), d);
    case DistanceMethod::AvgDist:
        return box.trace(glm::vec3(0.f), glm::normalize(x + avgDistance * d));
    default:
        return box.trace(x, d);
    }
}

// Per-case error record, printed in one line the lead can quote.
struct Worst {
    double err = 0.0;
    long n = 0, nonFinite = 0;
    double sum2 = 0.0;
    void add(glm::vec3 got, glm::vec3 want) {
        ++n;
        if (!finite3(got)) {
            ++nonFinite;
            return;
        }
        const double e = glm::length(got - want);
        err = std::max(err, e);
        sum2 += e * e;
    }
    double rms() const { return n ? std::sqrt(sum2 / double(n)) : 0.0; }
};

inline void report(const std::string& kase, const std::string& method, const char* path,
                   const Worst& w, double bound) {
    std::printf("[numerics] %-34s %-9s %-4s rays %8ld  worst %.3e  rms %.3e  bound %.1e%s\n",
                kase.c_str(), method.c_str(), path, w.n, w.err, w.rms(), bound,
                w.nonFinite ? "  NON-FINITE" : "");
    std::fflush(stdout);
}

// One ray for the GLSL harness. mode 0: `a` is l-hat as given. mode 1: the reflector
// pixel's own path: a = view ray v, b = shading normal n, c = geometric normal, l-hat =
// normalize(mirrorDirection(v, safeNormal(n, c))). mode 2: world space, as the reflector
// shader sees it: x holds the world position, a the eye; the shader subtracts the centre.
struct GpuRay {
    glm::vec3 x, a, b{0.f}, c{0.f};
};

struct GpuResult {
    glm::vec3 radiance;
    glm::vec3 lhat; // the reflected direction the shader used
    bool sky;       // no layer was hit
};

// Runs distance_lookup.glsl.h on the GPU (headless EGL) over a list of rays. The fetch
// functions are those of distance_reflector.frag: nearest texel for distance, bilinear
// radiance, same texture formats and sampler state as ReflectionProbeSystem.
class GpuLookup {
public:
    GpuLookup() : context_(gpu::GlContext::createHeadless()), vao_(gpu::VertexArray::create()) {}

    std::vector<GpuResult> run(const DistanceProbeAsset& a, const DistanceLookupConfig& c,
                               const std::vector<GpuRay>& rays, int mode = 0,
                               glm::vec3 centre = glm::vec3(0.f)) {
        const int count = int(rays.size());
        const int w = std::min(count, 512), h = (count + w - 1) / w;
        auto upload = [&](auto get) {
            std::vector<float> data(std::size_t(w) * std::size_t(h) * 4, 0.f);
            for (int i = 0; i < count; ++i) {
                const glm::vec3 v = get(rays[std::size_t(i)]);
                for (int k = 0; k < 3; ++k)
                    data[std::size_t(i) * 4 + std::size_t(k)] = v[k];
            }
            gpu::Texture t = gpu::Texture::create(GL_TEXTURE_2D);
            glTextureStorage2D(t.id(), 1, GL_RGBA32F, w, h);
            glTextureSubImage2D(t.id(), 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, data.data());
            return t;
        };
        gpu::Texture tx = upload([](const GpuRay& r) { return r.x; });
        gpu::Texture ta = upload([](const GpuRay& r) { return r.a; });
        gpu::Texture tb = upload([](const GpuRay& r) { return r.b; });
        gpu::Texture tc = upload([](const GpuRay& r) { return r.c; });

        const int layers = (c.features & kFeatureLayers) ? int(a.layers.size()) : 1;
        const int n = a.faceRes;
        gpu::Texture cube = gpu::Texture::create(GL_TEXTURE_2D_ARRAY);
        glTextureStorage3D(cube.id(), 1, GL_RGBA32F, n, n, 6 * layers);
        for (int L = 0; L < layers; ++L)
            for (int f = 0; f < 6; ++f)
                glTextureSubImage3D(cube.id(), 0, 0, 0, 6 * L + f, n, n, 1, GL_RGBA, GL_FLOAT,
                                    a.layers[std::size_t(L)].faces[std::size_t(f)].pixels.data());
        glTextureParameteri(cube.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(cube.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(cube.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(cube.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

        gpu::Program& prog = program(c.features);
        prog.setUniform("uLayers", 0);
        prog.setUniform("uX", 1);
        prog.setUniform("uA", 2);
        prog.setUniform("uB", 3);
        prog.setUniform("uC", 4);
        prog.setUniform("uMode", mode);
        DistanceLookupConfig placed = c; // the block as the system uploads it, at `centre`
        placed.params.centre = centre;
        params_.upload(placed);
        params_.bind(glsl::kDistanceParamsBinding);
        gpu::RenderTarget colour(w, h);
        gpu::RenderTarget dir(w, h);
        std::vector<GpuResult> out(rays.size());
        for (int pass = 0; pass < 2; ++pass) {
            const Image img = drawFullscreen(pass == 0 ? colour : dir, prog, vao_, [&] {
                prog.setUniform("uOutput", pass);
                glBindTextureUnit(0, cube.id());
                glBindTextureUnit(1, tx.id());
                glBindTextureUnit(2, ta.id());
                glBindTextureUnit(3, tb.id());
                glBindTextureUnit(4, tc.id());
            }); // row 0 at the top
            for (int i = 0; i < count; ++i) {
                const glm::vec4 p = img.rgba(i % w, h - 1 - i / w);
                if (pass == 0) {
                    out[std::size_t(i)].radiance = glm::vec3(p);
                    out[std::size_t(i)].sky = p.a > 1.5f;
                } else {
                    out[std::size_t(i)].lhat = glm::vec3(p);
                }
            }
        }
        return out;
    }

private:
    gpu::Program& program(std::uint32_t features) {
        auto it = programs_.find(features);
        if (it != programs_.end()) return it->second;
        auto bit = [&](std::uint32_t b) { return (features & b) ? "1" : "0"; };
        std::vector<std::string> defines; // from the method table, as the store builds them
        for (const DistanceMethodInfo& row : kDistanceMethods)
            if (row.define) defines.push_back(std::string(row.define) + "=" + bit(row.feature));
        defines.push_back(std::string("HAS_LAYERS=") + bit(kFeatureLayers));
        return programs_.emplace(features, buildFullscreenProgram("numerics", kFrag, defines))
            .first->second;
    }

    static constexpr const char* kFrag = R"(
#include "engine/core/glsl_device.glsl"
#include "engine/math/cube_face.glsl.h"
#include "engine/math/shading.glsl.h"
#include "components/reflection_probe/shaders/reflector_common.glsl.h"

#include "components/reflection_probe/distance/shaders/distance_lookup_types.glsl.h"
#include "components/reflection_probe/distance/shaders/distance_probe_gpu.glsl"

uniform sampler2D uX;
uniform sampler2D uA;
uniform sampler2D uB;
uniform sampler2D uC;
uniform int uMode;
uniform int uOutput;
out vec4 fragColor;

bool gSky = false;

vec3 fetchSky(vec3 dir) { gSky = true; return vec3(0.0); }

#include "components/reflection_probe/distance/shaders/distance_lookup.glsl.h"

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec3 x = texelFetch(uX, px, 0).xyz;
    vec3 a = texelFetch(uA, px, 0).xyz;
    vec3 lhat = a;
    if (uMode == 1) {
        lhat = normalize(mirrorDirection(a, safeNormal(texelFetch(uB, px, 0).xyz,
                                                       texelFetch(uC, px, 0).xyz)));
    } else if (uMode == 2) {
        vec3 world = x;
        x = world - probeCentre();
        vec3 v = normalize(world - a);
        lhat = normalize(mirrorDirection(v, safeNormal(texelFetch(uB, px, 0).xyz,
                                                       texelFetch(uC, px, 0).xyz)));
    }
    DistanceParams p = lookupParams();
    int fetches = 0;
    vec3 colour = probeRadiance(x, lhat, p, fetches);
    fragColor = uOutput == 0 ? vec4(colour, gSky ? 2.0 : 1.0) : vec4(lhat, 1.0);
}
)";

    std::unique_ptr<gpu::GlContext> context_;
    gpu::VertexArray vao_;
    gpu::UniformBuffer<glsl::DistanceParamsBlock> params_;
    std::map<std::uint32_t, gpu::Program> programs_;
};

// One GL context and program cache per test binary.
inline GpuLookup& gpuLookup() {
    static GpuLookup g;
    return g;
}

} // namespace specula::test
