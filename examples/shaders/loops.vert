#version 120
// Control flow test, vertex stage: the eye-space normal.
varying vec3 eye_normal;

void main() {
    eye_normal = gl_NormalMatrix * gl_Normal;
    gl_Position = ftransform();
}
