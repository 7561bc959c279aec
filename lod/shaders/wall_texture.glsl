// LOD0's wall texture: storeys and window bays drawn procedurally in facade coordinates
// (metres along the wall, height), filtered to their mean where a bay is smaller than a pixel.
// Roofs (faces that look up or down) keep their colour. lod/wall_texture_mean.h relies on the
// bay's 3 m height and on the fade ending at 0.75 of a bay a pixel: change them together.
#include "wall_colour.glsl"

vec3 wallTexture(vec3 albedo, vec3 n, vec3 local) {
    if (abs(n.z) >= 0.5) return albedo;
    vec2 along = normalize(vec2(-n.y, n.x));
    vec2 facade = vec2(dot(local.xy, along), local.z) / vec2(2.8, 3.0); // the residential grammar's defaults
    vec2 cell = fract(facade);
    vec2 width = fwidth(facade);
    vec2 inside = smoothstep(vec2(0.25, 0.3) - width, vec2(0.25, 0.3) + width, cell) *
                  (1.0 - smoothstep(vec2(0.75, 0.8) - width, vec2(0.75, 0.8) + width, cell));
    float window = mix(inside.x * inside.y, kWallWindowShare, clamp(max(width.x, width.y) * 2.0 - 0.5, 0.0, 1.0));
    return mix(albedo, kWallGlass, window);
}
