#version 110
#define PROCESSING_COLOR_SHADER // tells processing to stick some stuff in front of code

varying vec3 normal;
varying vec3 vertex_to_light; // points to light source

void main() { // in separate class
    const vec4 diffuseColor = vec4(1, 0, 0, 1); // red
    vec3 n_normal = normalize(normal);
    vec3 n_vertex_to_light = normalize(vertex_to_light);
    float diffuse = clamp(dot(n_normal, n_vertex_to_light), 0.0, 1.0); // <0 -> 0, >1 -> 1
    gl_FragColor = diffuse * diffuseColor;
}
