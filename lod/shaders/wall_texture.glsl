// LOD0's wall texture: storeys and window bays drawn procedurally in facade coordinates
// (metres along the wall, height), filtered to their mean where a bay is smaller than a pixel.
// Roofs (faces that look up or down) keep their colour. The bay's size and where the fade ends
// come from lod/wall_texture_mean.h, which finds the batches that show only the mean.
#include "wall_colour.glsl"
#include "wall_texture_sizes.glsl"

vec3 wallTexture(vec3 albedo, vec3 n, vec3 local) {
    if (abs(n.z) >= 0.5) return albedo;
    vec2 along = normalize(vec2(-n.y, n.x));
    vec2 facade = vec2(dot(local.xy, along), local.z) / kWallBay;
    vec2 cell = fract(facade);
    vec2 width = fwidth(facade);
    vec2 inside = smoothstep(vec2(0.25, 0.3) - width, vec2(0.25, 0.3) + width, cell) *
                  (1.0 - smoothstep(vec2(0.75, 0.8) - width, vec2(0.75, 0.8) + width, cell));
    // The fade to the mean runs over the last half cycle a pixel before kWallMeanCyclesPerPixel.
    float fade = clamp((max(width.x, width.y) - (kWallMeanCyclesPerPixel - 0.5)) * 2.0, 0.0, 1.0);
    float window = mix(inside.x * inside.y, kWallWindowShare, fade);
    return mix(albedo, kWallGlass, window);
}
