#version 110
varying vec2 textureCoord;
uniform sampler2D myTexture;
void main() {
    gl_FragColor = texture2D(myTexture, textureCoord);
}
