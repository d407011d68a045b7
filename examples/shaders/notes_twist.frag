#version 110
// The notes give no fragment program for the twist ("Input to Fragment: gl Color, texture coords -> output
// gl.FragColor"): the interpolated color is the fragment's color.
void main() {
    gl_FragColor = gl_Color;
}
