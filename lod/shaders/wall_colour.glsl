// LOD0's walls seen from afar: their window bays' glass and its share of a bay, so that the
// wall texture (wall_texture.glsl) and a far building's point (building_point.vert) show the
// same mean colour.
const vec3 kWallGlass = vec3(0.18, 0.22, 0.27);
const float kWallWindowShare = 0.25;

// The wall's colour where its bays are under a pixel.
vec3 wallTextureMean(vec3 albedo) {
    return mix(albedo, kWallGlass, kWallWindowShare);
}
