#version 110
varying vec2 leftCoord, rightCoord;
void main() {
    gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex;
    vec2 textureCoord = vec2(gl_MultiTexCoord0);
    leftCoord = textureCoord + vec2(-0.2, 0);      // on [0, 1] scale
    rightCoord = textureCoord + vec2(0.2, 0);
}
