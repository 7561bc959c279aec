#version 450 core
// Writes what an impostor view stores: albedo with coverage, and the shape-space normal with
// the depth toward the viewer (in units of the view radius, +1 nearest).
in vec3 vNormal;
in vec4 vAlbedo;
in float vDepth;

layout(location = 0) out vec4 outAlbedo;
layout(location = 1) out vec4 outNormalDepth;

void main() {
    vec3 n = normalize(gl_FrontFacing ? vNormal : -vNormal);
    outAlbedo = vec4(vAlbedo.rgb, 1.0);
    outNormalDepth = vec4(n, vDepth);
}
