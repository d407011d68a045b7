#version 120
// Control flow: a for loop over up to 4 directional lights that breaks at light_count, an if/else on a uniform
// (wrap_lighting: squared half-Lambert instead of Lambert), a user function, and a while loop that raises a rim
// term (1 - N.z) to the power rim_power by repeated multiplication.
uniform int light_count;    // 0 to 4 lights used
uniform vec3 light_dir[4];  // eye-space directions toward the lights (need not be unit length)
uniform vec3 light_color[4];
uniform bool wrap_lighting;
uniform int rim_power;      // 0 to 16

varying vec3 eye_normal;

float lambert(vec3 n, vec3 l) {
    return max(dot(n, normalize(l)), 0.0);
}

void main() {
    vec3 n = normalize(eye_normal);
    vec3 sum = vec3(0.05);
    for (int i = 0; i < 4; ++i) {
        if (i >= light_count) break;
        float d;
        if (wrap_lighting) {
            float h = 0.5 * dot(n, normalize(light_dir[i])) + 0.5;
            d = h * h;
        } else {
            d = lambert(n, light_dir[i]);
        }
        sum += d * light_color[i];
    }
    float rim = 1.0 - max(n.z, 0.0);
    float rim_term = 1.0;
    int k = 0;
    while (k < rim_power && k < 16) {
        rim_term *= rim;
        k++;
    }
    sum += 0.5 * rim_term;
    gl_FragColor = vec4(min(sum, 1.0), 1.0);
}
