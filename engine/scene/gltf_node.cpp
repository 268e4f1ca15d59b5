#include "gltf_node.h"

#include <algorithm>

namespace specula::gltf_internal {

namespace {

Transform decomposeMatrix(Context& ctx, const std::vector<double>& matrix, const std::string& nf) {
    Transform t;
    if (matrix.size() != 16) ctx.fail(nf + ".matrix", "expected 16 numbers");
    glm::mat4 m;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) {
            const double v = matrix[std::size_t(c * 4 + r)];
            if (!std::isfinite(v)) ctx.fail(nf + ".matrix", "non-finite value");
            m[c][r] = float(v);
        }
    t.translation = glm::vec3(m[3]);
    glm::vec3 cols[3] = {glm::vec3(m[0]), glm::vec3(m[1]), glm::vec3(m[2])};
    glm::vec3 s(glm::length(cols[0]), glm::length(cols[1]), glm::length(cols[2]));
    if (glm::determinant(glm::mat3(m)) < 0.f) s.x = -s.x;
    t.scale = s;
    if (std::abs(s.x) > 1e-12f && std::abs(s.y) > 1e-12f && std::abs(s.z) > 1e-12f) {
        const glm::mat3 r(cols[0] / s.x, cols[1] / s.y, cols[2] / s.z);
        t.rotation = glm::normalize(glm::quat_cast(r));
        const glm::mat3 rtr = glm::transpose(r) * r;
        float dev = 0.f;
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b)
                dev = std::max(dev, std::abs(rtr[a][b] - (a == b ? 1.f : 0.f)));
        if (dev > 1e-3f) ctx.warn(nf + ".matrix", "shear dropped when decomposing into TRS");
    }
    return t;
}

// Copies `v` (absent: leaves `dst` alone) after checking it has `n` finite numbers.
void readNumbers(const Context& ctx, const std::vector<double>& v, std::size_t n,
                 const std::string& field, float* dst) {
    if (v.empty()) return;
    if (v.size() != n) ctx.fail(field, "expected " + std::to_string(n) + " numbers");
    for (std::size_t i = 0; i < n; ++i) {
        if (!std::isfinite(v[i])) ctx.fail(field, "non-finite value");
        dst[i] = float(v[i]);
    }
}

} // namespace

Transform localTransform(Context& ctx, const tinygltf::Node& node, const std::string& nf) {
    if (!node.matrix.empty()) return decomposeMatrix(ctx, node.matrix, nf);
    Transform t;
    readNumbers(ctx, node.translation, 3, nf + ".translation", &t.translation.x);
    readNumbers(ctx, node.scale, 3, nf + ".scale", &t.scale.x);
    float q[4] = {0.f, 0.f, 0.f, 1.f}; // glTF order x, y, z, w
    readNumbers(ctx, node.rotation, 4, nf + ".rotation", q);
    const glm::quat rot(q[3], q[0], q[1], q[2]);
    const float len = glm::length(rot);
    if (!(len > 1e-6f)) ctx.fail(nf + ".rotation", "expected a unit quaternion, got length 0");
    t.rotation = rot / len;
    return t;
}

std::optional<Camera> camera(Context& ctx, int index, const std::string& from) {
    const auto& c = ctx.at(ctx.model().cameras, index, "cameras", from);
    const std::string cf = idx("cameras", std::size_t(index));
    if (c.type != "perspective") {
        ctx.warn(cf, "camera type '" + c.type + "' skipped; only perspective is loaded");
        return std::nullopt;
    }
    const auto& p = c.perspective;
    if (!std::isfinite(p.yfov) || p.yfov <= 0.0 || p.yfov >= 3.14159)
        ctx.fail(cf + ".perspective.yfov", "expected an angle in (0, pi) radians");
    if (!std::isfinite(p.znear) || p.znear <= 0.0)
        ctx.fail(cf + ".perspective.znear", "expected a positive number");
    if (!std::isfinite(p.aspectRatio) || p.aspectRatio < 0.0)
        ctx.fail(cf + ".perspective.aspectRatio", "expected a positive number");
    if (!std::isfinite(p.zfar) || (p.zfar != 0.0 && p.zfar <= p.znear))
        ctx.fail(cf + ".perspective.zfar", "expected a number larger than znear");
    Camera cam;
    cam.yfov = float(p.yfov);
    cam.aspect = float(p.aspectRatio);
    cam.znear = float(p.znear);
    // glTF leaves zfar out for an infinite projection; keep the component's finite
    // default, far enough for every scene this project draws.
    if (p.zfar > 0.0) cam.zfar = float(p.zfar);
    return cam;
}

} // namespace specula::gltf_internal
