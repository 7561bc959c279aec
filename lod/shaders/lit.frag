#version 450 core
// LOD4 meshes (tree parts among them): the colour their vertices lit (terminal_mesh.vert).

in vec3 vColour;
layout(location = 0) out vec4 colour;

void main() {
    colour = vec4(vColour, 1.0);
}
