#version 110
// Mipmapped texturing: texture2D with the implicit level of detail (from the screen-space derivatives of the
// coordinates) at gl_TexCoord[0] * scale; a large scale repeats the texture many times so that distant texels
// minify into the MIP chain.
uniform sampler2D color_map;  // texture unit 0
uniform float scale;

void main() {
    gl_FragColor = texture2D(color_map, gl_TexCoord[0].st * scale);
}
