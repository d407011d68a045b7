#version 110
// Per-pixel Phong lighting from gl_LightSource[0] and gl_FrontMaterial (OpenGL's lighting equation with the reflection
// vector): emission + scene ambient + light ambient + diffuse (N.L) + specular (R.V)^shininess. Back faces are lit
// with the flipped normal.
varying vec3 eye_position;
varying vec3 eye_normal;

void main() {
    vec3 n = normalize(eye_normal);
    if (!gl_FrontFacing) n = -n;
    vec4 light = gl_LightSource[0].position;
    vec3 l = light.w == 0.0 ? normalize(light.xyz) : normalize(light.xyz - eye_position);
    vec3 v = normalize(-eye_position);
    vec3 r = reflect(-l, n);
    float diffuse = max(dot(n, l), 0.0);
    float rv = dot(r, v);
    float specular = 0.0;
    if (diffuse > 0.0 && rv > 0.0) specular = pow(rv, gl_FrontMaterial.shininess);
    vec4 color = gl_FrontMaterial.emission + gl_LightModel.ambient * gl_FrontMaterial.ambient +
                 gl_LightSource[0].ambient * gl_FrontMaterial.ambient +
                 diffuse * gl_LightSource[0].diffuse * gl_FrontMaterial.diffuse +
                 specular * gl_LightSource[0].specular * gl_FrontMaterial.specular;
    gl_FragColor = vec4(color.rgb, gl_FrontMaterial.diffuse.a);
}
