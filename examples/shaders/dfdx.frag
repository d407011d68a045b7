#version 110
// Anti-aliased stripes: a plaid of stripes across u and v, `frequency` of each per unit, half the period wide. Each
// edge is smoothed over one pixel: the footprint of u is the length of (dFdx, dFdy), that of v is fwidth (the sum of
// their absolute values).
uniform float frequency;
uniform vec3 stripe_color;
uniform vec3 background_color;

varying vec2 uv;

float stripe(float s, float width) {
    float d = abs(fract(s) - 0.5);  // 0 at the stripe's center, 0.5 halfway between stripes
    return 1.0 - smoothstep(0.25 - 0.5 * width, 0.25 + 0.5 * width, d);
}

void main() {
    float s = uv.x * frequency;
    float t = uv.y * frequency;
    float s_width = length(vec2(dFdx(s), dFdy(s)));
    float t_width = fwidth(t);
    float coverage = max(stripe(s, s_width), 0.6 * stripe(t, t_width));
    gl_FragColor = vec4(mix(background_color, stripe_color, coverage), 1.0);
}
