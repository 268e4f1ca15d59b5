#pragma once
// What the host-API tests share: a host's full-screen shader that ray casts one sphere per
// pixel (the GLSL after Specula's library, before the test's own main) and the same ray cast
// on the CPU, so each pixel's reflector point and eye ray are known to the twin.
#include "engine/gpu/gl_objects.h"

#include <cmath>

#include <glm/glm.hpp>

namespace specula::test {

// Uniforms uInvViewProj, uEye, uSphere (centre, radius) and uSize (the viewport), and
// sphereHit: the eye ray d through this pixel, its first hit p, and the pixel's NDC.
inline constexpr const char* kHostSphereGlsl = R"(
uniform mat4 uInvViewProj;
uniform vec3 uEye;
uniform vec4 uSphere;
uniform vec2 uSize;
out vec4 colour;
bool sphereHit(out vec3 p, out vec3 d, out vec2 ndc) {
    ndc = gl_FragCoord.xy / uSize * 2.0 - 1.0;
    vec4 far = uInvViewProj * vec4(ndc, 1.0, 1.0);
    d = normalize(far.xyz / far.w - uEye);
    vec3 o = uEye - uSphere.xyz;
    float b = dot(o, d), h = b * b - dot(o, o) + uSphere.w * uSphere.w;
    float t = h >= 0.0 ? -b - sqrt(h) : -1.0;
    p = uEye + t * d;
    return t > 0.0;
}
)";

// The host's main after kHostSphereGlsl: the sphere as a mirror, black around it.
inline constexpr const char* kHostMirrorSphereMain = R"(
void main() {
    vec3 p, d;
    vec2 ndc;
    if (!sphereHit(p, d, ndc)) { colour = vec4(0.0); return; }
    colour = vec4(speculaReflect(p, p - uSphere.xyz, d, 0.0), 1.0);
}
)";

struct HostSphereView {
    glm::mat4 invViewProj;
    glm::vec3 eye;
    glm::vec4 sphere; // centre, radius
    int width, height;

    void setUniforms(gpu::Program& prog) const {
        prog.setUniform("uInvViewProj", invViewProj);
        prog.setUniform("uEye", eye);
        prog.setUniform("uSize", glm::vec2(width, height));
        glProgramUniform4f(prog.id(), prog.uniformLocation("uSphere"), sphere.x, sphere.y, sphere.z,
                           sphere.w);
    }
    // sphereHit at pixel (x, y) of the read-back image (row 0 at the top: GL row h - 1 - y).
    bool hit(int x, int y, glm::vec3& p, glm::vec3& d, glm::vec2& ndc) const {
        ndc = glm::vec2((x + 0.5f) / float(width) * 2.f - 1.f,
                        (float(height - 1 - y) + 0.5f) / float(height) * 2.f - 1.f);
        const glm::vec4 far = invViewProj * glm::vec4(ndc, 1.f, 1.f);
        d = glm::normalize(glm::vec3(far) / far.w - eye);
        const glm::vec3 o = eye - glm::vec3(sphere);
        const float b = glm::dot(o, d), h = b * b - glm::dot(o, o) + sphere.w * sphere.w;
        const float t = h >= 0.f ? -b - std::sqrt(h) : -1.f;
        p = eye + t * d;
        return t > 0.f;
    }
};

} // namespace specula::test
