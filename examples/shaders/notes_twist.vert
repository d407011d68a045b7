#version 110
uniform float twist;

void main() {
    vec4 pos = gl_ModelViewProjectionMatrix * gl_Vertex;
    vec4 center = vec4(512, 512, 0, 0); // center of 1024x1024 2D space
    vec2 diff = vec2(pos.x - center.x, pos.y - center.y);
    float angle = twist * length(diff);
    float c = cos(angle), s = sin(angle);
    gl_Position.x = c * pos.x - s * pos.y;
    gl_Position.y = s * pos.x + c * pos.y;
    gl_Position.z = pos.z; gl_Position.w = pos.w;
    gl_FrontColor = gl_BackColor = gl_Color; // copy color to output
}
