#version 450 core
// A far tree's point: its colour, lit in the vertex shader.
flat in vec3 vColour;
layout(location = 0) out vec4 colour;

void main() {
    colour = vec4(vColour, 1.0);
}
