// Environment geometry. Attribute and uniform names follow the contract in
// engine/render/scene_renderer.h.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;

uniform mat4 uViewProj;
uniform mat4 uModel;
uniform mat3 uNormalMatrix;

out vec3 vNormal;
out vec2 vUv;

void main() {
    vNormal = uNormalMatrix * aNormal;
    vUv = aUv;
    gl_Position = uViewProj * (uModel * vec4(aPosition, 1.0));
}
