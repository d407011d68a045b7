#version 110
// Per-pixel Phong lighting, vertex stage: the eye-space position and normal for the fragment stage.
varying vec3 eye_position;
varying vec3 eye_normal;

void main() {
    eye_position = vec3(gl_ModelViewMatrix * gl_Vertex);
    eye_normal = gl_NormalMatrix * gl_Normal;
    gl_Position = ftransform();
}
