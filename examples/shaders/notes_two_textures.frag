#version 110
#define PROCESSING_TEXTURE_SHADER
varying vec2 leftCoord, rightCoord;
uniform sampler2D myTexture;
void main() {
    vec4 leftColor = texture2D(myTexture, leftCoord), rightColor = texture2D(myTexture, rightCoord);
    gl_FragColor = 0.5 * (leftColor + rightColor);
}
