#version 450 core
// One terminal mesh seen from one direction, at its nominal size: the impostor baker's view
// and the reference it is tested against.
#include "gpu_types.h"

layout(location = HEXLOD_ATTRIBUTE_POSITION) in vec3 unitPosition;
layout(location = HEXLOD_ATTRIBUTE_NORMAL) in vec3 shapeNormal;
layout(location = HEXLOD_ATTRIBUTE_COLOR) in vec4 albedo;

uniform mat4 unitToClip;  // nominal scale, view and orthographic projection
uniform mat4 unitToView;  // nominal scale and view, for the depth channel
uniform float viewRadius; // the fitted bounding sphere's radius, in metres

out vec3 vNormal;
out vec4 vAlbedo;
out float vDepth;

void main() {
    gl_Position = unitToClip * vec4(unitPosition, 1.0);
    vNormal = shapeNormal;
    vAlbedo = albedo;
    // View space looks down -z: a larger z is closer to the viewer.
    vDepth = (unitToView * vec4(unitPosition, 1.0)).z / viewRadius;
}
