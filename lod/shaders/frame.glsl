// Frame constants every draw pass reads (uniform block 1; FrameUniforms in frame_renderer.cpp)
// and the one lighting model all LODs share: a directional sun plus ambient, on albedo and a
// world normal, so a terminal shades alike as geometry, impostor or per-pixel facade.
layout(std140, binding = 1) uniform FrameBlock {
    mat4 viewProjection;  // camera-relative world (the camera at the origin) to clip
    vec4 sunDirection;    // xyz: toward the sun, unit; w: ambient share
    vec4 sunColour;       // rgb
    vec4 skyColour;       // rgb: the background, and the colour distance fades to; w: fog density
    vec4 viewport;        // width, height, 1 / width, 1 / height
};

struct GpuShape {
    vec4 nominalSize; // xyz: the size normals are metric at; w: impostor layer, -1 none
    vec4 boundsMin, boundsMax;
};

// Exponential distance fog keeps far cells from shimmering against the sky.
float fogAmount(vec3 cameraRelative) {
    return 1.0 - exp(-skyColour.w * length(cameraRelative));
}

// `fog`: fogAmount, where a pass computes it apart (per vertex, LOD4).
vec3 shadeFogged(vec3 albedo, vec3 normal, float fog) {
    float diffuse = max(dot(normal, sunDirection.xyz), 0.0);
    vec3 lit = albedo * (sunDirection.w + (1.0 - sunDirection.w) * diffuse * sunColour.rgb);
    return mix(lit, skyColour.rgb, fog);
}

vec3 shade(vec3 albedo, vec3 normal, vec3 cameraRelative) {
    return shadeFogged(albedo, normal, fogAmount(cameraRelative));
}

// Rotation of v by the unit quaternion q (x, y, z, w).
vec3 rotateByQuaternion(vec4 q, vec3 v) {
    vec3 t = 2.0 * cross(q.xyz, v);
    return v + q.w * t + cross(q.xyz, t);
}

// The normal of a mesh stored at the shape's nominal size, on a scope of size `scope`
// (render/terminal_mesh.h: the inverse transpose of the stretch).
vec3 scopeNormal(vec3 stored, vec3 nominal, vec3 scope) {
    vec3 ratio;
    for (int i = 0; i < 3; ++i) ratio[i] = nominal[i] <= 0.0 ? 1.0 : (scope[i] <= 0.0 ? 1e4 : nominal[i] / scope[i]);
    vec3 n = ratio * stored;
    return length(n) > 0.0 ? normalize(n) : vec3(0.0, 0.0, 1.0);
}
