#version 120
// Procedural bricks (after the Orange Book's brick shader) on the object's xy plane: rows of bricks of brick_size,
// every other row offset by half a brick, brick_pct of each cell brick and the rest mortar. The mortar of one cell in
// three (by column and row) is discarded, so the draw has holes.
uniform vec3 brick_color;
uniform vec3 mortar_color;
uniform vec2 brick_size;  // a cell's width and height, object units
uniform vec2 brick_pct;   // the fraction of a cell that is brick, in x and y

varying vec2 object_position;
varying float light_intensity;

void main() {
    vec2 position = object_position / brick_size;
    if (fract(position.y * 0.5) > 0.5) position.x += 0.5;  // offset every other row
    vec2 cell = floor(position);
    vec2 in_cell = fract(position);
    vec2 use_brick = step(in_cell, brick_pct);
    float brick = use_brick.x * use_brick.y;
    if (brick < 0.5 && mod(cell.x + cell.y, 3.0) < 0.5) discard;
    vec3 color = mix(mortar_color, brick_color, brick);
    gl_FragColor = vec4(color * light_intensity, 1.0);
}
