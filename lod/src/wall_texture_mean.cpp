#include "hexlod/lod/wall_texture_mean.h"

#include <algorithm>
#include <cstdio>

namespace hexlod::lod {

std::string wallTextureSizesGlsl() {
    char text[160];
    std::snprintf(text, sizeof text,
                  "const vec2 kWallBay = vec2(%.9g, %.9g); // metres along the wall, up it\n"
                  "const float kWallMeanCyclesPerPixel = %.9g;\n",
                  double(kWallBayMetres), double(kWallStoreyMetres), double(kWallMeanCyclesPerPixel));
    return text;
}

bool wallTextureIsMean(const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& forward,
                       float screenScale) {
    if (!(screenScale > 0.0f)) return false;
    // Depth is linear, so the box's nearest depth is at a corner: per axis, the smaller end.
    float nearest = 0.0f;
    for (int axis = 0; axis < 3; ++axis)
        nearest += std::min(lo[axis] * forward[axis], hi[axis] * forward[axis]);
    return nearest >= kWallMeanCyclesPerPixel * std::max(kWallBayMetres, kWallStoreyMetres) * screenScale;
}

} // namespace hexlod::lod
