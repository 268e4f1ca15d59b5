#pragma once
// One pinhole camera for the rasteriser and the ray tracer, so both agree on conventions:
// right-handed, Y up, looking down -Z in view space, OpenGL clip space. Image row 0 is the
// top of the picture; pixel (x, y) is sampled at its centre.
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace specula {

struct CameraView {
    glm::mat4 view{1.f};
    glm::mat4 proj{1.f};
    int width = 0;
    int height = 0;

    glm::vec3 eye() const { return glm::vec3(glm::inverse(view)[3]); }
    glm::mat4 viewProj() const { return proj * view; }

    static CameraView lookAt(glm::vec3 eye, glm::vec3 target, glm::vec3 up, float yfovRadians,
                             int width, int height, float znear = 0.05f, float zfar = 500.f) {
        CameraView c;
        c.view = glm::lookAt(eye, target, up);
        c.proj = glm::perspective(yfovRadians, float(width) / float(height), znear, zfar);
        c.width = width;
        c.height = height;
        return c;
    }

    // World-space ray through the centre of pixel (x, y), y = 0 at the top.
    void primaryRay(int x, int y, glm::vec3& origin, glm::vec3& direction) const {
        const glm::mat4 inv = glm::inverse(viewProj());
        const float ndcX = (float(x) + 0.5f) / float(width) * 2.f - 1.f;
        const float ndcY = 1.f - (float(y) + 0.5f) / float(height) * 2.f;
        glm::vec4 nearP = inv * glm::vec4(ndcX, ndcY, -1.f, 1.f);
        glm::vec4 farP = inv * glm::vec4(ndcX, ndcY, 1.f, 1.f);
        nearP /= nearP.w;
        farP /= farP.w;
        origin = glm::vec3(nearP);
        direction = glm::normalize(glm::vec3(farP - nearP));
    }
};

} // namespace specula
