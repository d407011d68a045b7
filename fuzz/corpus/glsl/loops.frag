uniform sampler2D tex;
uniform samplerCube env;
uniform int n;
uniform float w[4];
varying vec3 normal;
float f(inout float x) { x *= 2.0; return x > 1.0 ? x - 1.0 : x; }
void main() {
  vec4 c = texture2D(tex, gl_TexCoord[0].st * 3.0) + textureCube(env, normal);
  float s = 0.0;
  for (int i = 0; i < 8; ++i) {
    if (i >= n) break;
    if (mod(float(i), 2.0) > 0.5) continue;
    s += w[i / 2] * f(c.x);
  }
  int k = 0;
  do { s += dFdx(s) + dFdy(c.y); k++; } while (k < 3);
  if (s < 0.0) discard;
  gl_FragColor = vec4(s, fwidth(c.x), c.z, 1.0) * mat4(1.0);
}
