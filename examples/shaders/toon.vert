#version 120
// Toon shading, vertex stage: the eye-space normal and position.
varying vec3 eye_normal;
varying vec3 eye_position;

void main() {
    eye_normal = gl_NormalMatrix * gl_Normal;
    eye_position = vec3(gl_ModelViewMatrix * gl_Vertex);
    gl_Position = ftransform();
}
