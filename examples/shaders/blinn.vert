#version 120
// Per-pixel Blinn-Phong lighting, vertex stage: the eye-space position and normal for the fragment stage.
varying vec3 eye_position;
varying vec3 eye_normal;

void main() {
    vec4 p = gl_ModelViewMatrix * gl_Vertex;
    eye_position = p.xyz / p.w;
    eye_normal = gl_NormalMatrix * gl_Normal;
    gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex;
}
