// Where LOD0's wall texture shows only its mean. wall_texture.glsl draws storeys and window
// bays in facade coordinates (metres over 2.8 along the wall, over 3 up it) and fades them to
// their mean colour where those coordinates change by 0.75 or more across a pixel. A wall at a
// depth of d metres along the view spans about d / screenScale metres a pixel where it faces the
// camera, and more where it does not, so beyond a depth of 0.75 * 3 * screenScale metres every
// pixel of it shows the mean. A batch whose box lies wholly beyond that depth is shaded with
// the mean per vertex (volume.vert's VOLUME_SHADING 3), as the plain shells are, and its
// fragments skip the texture: in the far overview that was a seventh of LOD0's pass
// (docs/BENCHMARKS.md, "LOD0's wall texture at its mean per vertex").
#pragma once

#include <glm/vec3.hpp>

namespace hexlod::lod {

inline constexpr float kWallStoreyMetres = 3.0f;        // wall_texture.glsl's bay height (its larger side)
inline constexpr float kWallMeanCyclesPerPixel = 0.75f; // where wall_texture.glsl's fade to the mean ends

// Whether the box [lo, hi] (camera-relative metres) lies wholly beyond that depth along the
// view direction `forward` (unit length); `screenScale` is the pixels one metre spans at one
// metre's distance. False for NaN or non-positive inputs.
bool wallTextureIsMean(const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& forward, float screenScale);

} // namespace hexlod::lod
