#version 110
// Normal mapping with environment reflection: the tangent-space normal from normal_map (RGB = (n + 1) / 2) is taken
// to eye space with the interpolated frame (tangent made orthogonal to the normal, bitangent = N x T), lit by
// gl_LightSource[0] (diffuse, gl_FrontMaterial's diffuse color), and mixed with the environment seen along the
// reflected view vector (eye space indexes the cube map) by `reflectivity`.
uniform sampler2D normal_map;     // texture unit 0
uniform samplerCube environment;  // texture unit 1
uniform float reflectivity;       // 0: lit surface only, 1: mirror

varying vec3 eye_position;
varying vec3 eye_normal;
varying vec3 eye_tangent;
varying vec2 uv;

void main() {
    vec3 n = normalize(eye_normal);
    vec3 t = normalize(eye_tangent - dot(eye_tangent, n) * n);
    vec3 b = cross(n, t);
    vec3 tangent_normal = texture2D(normal_map, uv).xyz * 2.0 - 1.0;
    vec3 bumped = normalize(tangent_normal.x * t + tangent_normal.y * b + tangent_normal.z * n);
    vec4 light = gl_LightSource[0].position;
    vec3 l = normalize(light.xyz - light.w * eye_position);
    float diffuse = max(dot(bumped, l), 0.0);
    vec3 lit = gl_FrontMaterial.diffuse.rgb * (0.15 + 0.85 * diffuse);
    vec3 reflected = reflect(normalize(eye_position), bumped);
    vec3 environment_color = textureCube(environment, reflected).rgb;
    gl_FragColor = vec4(mix(lit, environment_color, reflectivity), 1.0);
}
