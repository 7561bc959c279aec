#version 450 core
// Geometry in metric shape space seen along one direction, orthographically: an impostor
// view as the baker renders it, and the reference it is tested against.
#include "gpu_types.h"

layout(location = HEXLOD_ATTRIBUTE_POSITION) in vec3 shapePosition;
layout(location = HEXLOD_ATTRIBUTE_NORMAL) in vec3 shapeNormal;
layout(location = HEXLOD_ATTRIBUTE_COLOR) in vec4 albedo;

uniform mat4 shapeToClip; // view and orthographic projection of the bounding sphere
uniform vec4 depthPlane;  // dot(depthPlane.xyz, p) + depthPlane.w: depth toward the viewer / radius

out vec3 vNormal;
out vec4 vAlbedo;
out float vDepth;

void main() {
    gl_Position = shapeToClip * vec4(shapePosition, 1.0);
    vNormal = shapeNormal;
    vAlbedo = albedo;
    vDepth = dot(depthPlane.xyz, shapePosition) + depthPlane.w;
}
