#version 120
// Per-pixel Blinn-Phong lighting from gl_LightSource[0] and gl_FrontMaterial: the specular term is
// (N.H)^shininess with the half vector H = normalize(L + V), through the gl_FrontLightProduct built-ins.
varying vec3 eye_position;
varying vec3 eye_normal;

void main() {
    vec3 n = normalize(eye_normal);
    if (!gl_FrontFacing) n = -n;
    vec4 light = gl_LightSource[0].position;
    vec3 l = normalize(light.xyz - light.w * eye_position);
    vec3 v = normalize(-eye_position);
    vec3 h = normalize(l + v);
    float diffuse = max(dot(n, l), 0.0);
    float nh = dot(n, h);
    float specular = diffuse > 0.0 && nh > 0.0 ? pow(nh, gl_FrontMaterial.shininess) : 0.0;
    vec4 color = gl_FrontLightModelProduct.sceneColor + gl_FrontLightProduct[0].ambient +
                 diffuse * gl_FrontLightProduct[0].diffuse + specular * gl_FrontLightProduct[0].specular;
    gl_FragColor = vec4(clamp(color.rgb, 0.0, 1.0), gl_FrontMaterial.diffuse.a);
}
