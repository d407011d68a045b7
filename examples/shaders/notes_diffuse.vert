#version 110
varying vec3 normal;
varying vec3 vertex_to_light; // points to light source

void main() {
    gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex; // transform + project into 2D
    normal = gl_NormalMatrix * gl_Normal;
    vec4 vertex_modelview = gl_ModelViewMatrix * gl_Vertex;
    vertex_to_light = vec3(gl_LightSource[0].position - vertex_modelview);
}
