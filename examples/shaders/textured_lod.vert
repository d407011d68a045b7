#version 110
// Mipmapped texturing, vertex stage: the texture coordinates through gl_TexCoord[0].
void main() {
    gl_TexCoord[0] = gl_MultiTexCoord0;
    gl_Position = ftransform();
}
