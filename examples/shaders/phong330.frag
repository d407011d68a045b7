#version 330
// Per-pixel Phong lighting in GLSL 3.30: one light (eye space, w = 0 directional, 1 point), ambient + diffuse (N.L)
// + specular (R.V)^shininess.
uniform vec4 light_position;
uniform vec3 light_color;
uniform vec3 ambient_color;
uniform vec3 diffuse_color;
uniform vec3 specular_color;
uniform float shininess;

in vec3 eye_position;
in vec3 eye_normal;

out vec4 frag_color;

void main() {
    vec3 n = normalize(eye_normal);
    if (!gl_FrontFacing) n = -n;
    vec3 l = normalize(light_position.xyz - light_position.w * eye_position);
    vec3 v = normalize(-eye_position);
    vec3 r = reflect(-l, n);
    float diffuse = max(dot(n, l), 0.0);
    float rv = dot(r, v);
    float specular = diffuse > 0.0 && rv > 0.0 ? pow(rv, shininess) : 0.0;
    vec3 color = ambient_color + light_color * (diffuse * diffuse_color + specular * specular_color);
    frag_color = vec4(color, 1.0);
}
