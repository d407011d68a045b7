#version 110
// Anti-aliased stripes, vertex stage: the texture coordinates.
varying vec2 uv;

void main() {
    uv = gl_MultiTexCoord0.st;
    gl_Position = ftransform();
}
