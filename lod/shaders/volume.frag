#version 450 core
// LOD0: a base volume with a wall texture: storeys and window bays drawn procedurally in
// facade coordinates (metres along the wall, height), so LOD0 needs no image and reads as
// a building from afar. Under terminals (LOD2-4 cells) the walls are plain.
#include "frame.glsl"

uniform uint wallTexture;

in vec3 vNormal;
in vec3 vAlbedo;
in vec3 vPosition;
in vec3 vLocal;
layout(location = 0) out vec4 colour;

void main() {
    vec3 n = normalize(gl_FrontFacing ? vNormal : -vNormal);
    vec3 albedo = vAlbedo;
    if (wallTexture != 0u && abs(n.z) < 0.5) {
        vec2 along = normalize(vec2(-n.y, n.x));
        vec2 facade = vec2(dot(vLocal.xy, along), vLocal.z);
        // 3 m storeys, 2.8 m bays: the residential grammar's defaults.
        vec2 cell = fract(facade / vec2(2.8, 3.0));
        // Filtered edges: the pattern fades to its mean where a bay is smaller than a pixel.
        vec2 width = fwidth(facade / vec2(2.8, 3.0));
        vec2 inside = smoothstep(vec2(0.25, 0.3) - width, vec2(0.25, 0.3) + width, cell) *
                      (1.0 - smoothstep(vec2(0.75, 0.8) - width, vec2(0.75, 0.8) + width, cell));
        float window = inside.x * inside.y;
        float blur = clamp(max(width.x, width.y) * 2.0 - 0.5, 0.0, 1.0);
        window = mix(window, 0.25, blur);
        albedo = mix(albedo, vec3(0.18, 0.22, 0.27), window);
    }
    colour = vec4(shade(albedo, n, vPosition), 1.0);
}
