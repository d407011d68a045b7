#version 110
#define PROCESSING_TEXTURE_SHADER
varying vec2 textureCoord;
void main() {
    gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex;
    textureCoord = vec2(gl_MultiTexCoord0);
}
