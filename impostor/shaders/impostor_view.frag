#version 450 core
// Reconstructs one shape seen along `forward` over the whole target.
uniform sampler2DArray impostorAlbedo, impostorNormalDepth;
uniform usampler2D impostorTableViews;
uniform sampler2D impostorTableWeights;
uniform uvec4 impostorLayout;
#include "impostor_views.glsl"

uniform uint layer;
uniform vec3 forward;
uniform uint iterations;
uniform uint centralOnly;
in vec2 vPosition;
layout(location = 0) out vec4 outAlbedo;
layout(location = 1) out vec4 outNormalDepth;

void main() {
    vec3 right, up;
    impostorBasis(forward, impostorLayout.w, right, up);
    uvec4 views;
    vec4 weights;
    impostorViews(forward, views, weights);
    if (centralOnly != 0u) weights = vec4(1.0, 0.0, 0.0, 0.0);
    outAlbedo = impostorReconstruct(layer, vPosition.x * right + vPosition.y * up, forward, views, weights,
                                    centralOnly != 0u ? 1u : 4u, iterations, outNormalDepth);
}
