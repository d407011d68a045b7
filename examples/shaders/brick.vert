#version 120
// Procedural bricks, vertex stage: the object-space position (the pattern is fixed to the object) and a per-vertex
// light intensity (diffuse + a little specular from gl_LightSource[0]).
varying vec2 object_position;
varying float light_intensity;

void main() {
    vec3 p = vec3(gl_ModelViewMatrix * gl_Vertex);
    vec3 n = normalize(gl_NormalMatrix * gl_Normal);
    vec4 light = gl_LightSource[0].position;
    vec3 l = normalize(light.xyz - light.w * p);
    vec3 r = reflect(-l, n);
    vec3 v = normalize(-p);
    float specular = 0.0;
    if (dot(n, l) > 0.0) specular = pow(max(dot(r, v), 0.0), 16.0);
    light_intensity = 0.25 + 0.7 * max(dot(n, l), 0.0) + 0.3 * specular;
    object_position = gl_Vertex.xy;
    gl_Position = ftransform();
}
