#version 450 core
// A far tree's or building's point: its colour, lit in the vertex shader (tree_point.vert,
// building_point.vert).
flat in vec3 vColour;
layout(location = 0) out vec4 colour;

void main() {
    colour = vec4(vColour, 1.0);
}
