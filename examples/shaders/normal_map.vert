#version 110
// Normal mapping with environment reflection, vertex stage: the eye-space frame (normal, tangent), position and the
// texture coordinates. `tangent` is the object-space direction of increasing u.
attribute vec3 tangent;
varying vec3 eye_position;
varying vec3 eye_normal;
varying vec3 eye_tangent;
varying vec2 uv;

void main() {
    eye_position = vec3(gl_ModelViewMatrix * gl_Vertex);
    eye_normal = gl_NormalMatrix * gl_Normal;
    eye_tangent = gl_NormalMatrix * tangent;
    uv = gl_MultiTexCoord0.st;
    gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex;
}
