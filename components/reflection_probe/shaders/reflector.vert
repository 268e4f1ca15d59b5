// Reflector geometry for the probe pass (attribute/uniform contract: scene_renderer.h).
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;

uniform mat4 uViewProj;
uniform mat4 uModel;
uniform mat3 uNormalMatrix;

out vec3 vWorldPos;
out vec3 vNormal;
// TEXCOORD_0 (zero when the mesh has none), where a roughness map is read
// (reflector_roughness.glsl.h); fragment shaders without a map leave it unread.
out vec2 vUv;

void main() {
    vec4 world = uModel * vec4(aPosition, 1.0);
    vWorldPos = world.xyz;
    vNormal = uNormalMatrix * aNormal;
    vUv = aUv;
    gl_Position = uViewProj * world;
}
