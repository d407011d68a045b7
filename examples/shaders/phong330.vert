#version 330
// Per-pixel Phong lighting in GLSL 3.30 (no compatibility built-ins), vertex stage.
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;

uniform mat4 model_view;
uniform mat4 projection;
uniform mat3 normal_matrix;  // inverse transpose of model_view's upper 3x3

out vec3 eye_position;
out vec3 eye_normal;

void main() {
    vec4 p = model_view * vec4(position, 1.0);
    eye_position = p.xyz;
    eye_normal = normal_matrix * normal;
    gl_Position = projection * p;
}
