#version 450 core
// A full-target quad in the frame of one direction: the GPU reconstruction of a whole view,
// for tests and contact sheets.
out vec2 vPosition; // [-1, 1]^2, y up
void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
    vPosition = corner;
    gl_Position = vec4(corner, 0.0, 1.0);
}
