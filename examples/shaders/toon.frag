#version 120
// Toon shading: the diffuse term N.L of gl_LightSource[0] quantized into 4 bands (1/4, 2/4, 3/4, 1 of base_color).
uniform vec3 base_color;
varying vec3 eye_normal;
varying vec3 eye_position;

void main() {
    vec3 n = normalize(eye_normal);
    vec4 light = gl_LightSource[0].position;
    vec3 l = normalize(light.xyz - light.w * eye_position);
    float diffuse = max(dot(n, l), 0.0);
    float band = min(floor(diffuse * 4.0), 3.0);  // 0, 1, 2 or 3
    gl_FragColor = vec4(base_color * ((band + 1.0) / 4.0), 1.0);
}
