// Where LOD0's wall texture shows only its mean. wall_texture.glsl draws storeys and window
// bays in facade coordinates (metres over the bay's width along the wall, over its height up
// it) and fades them to their mean colour where those coordinates change by
// kWallMeanCyclesPerPixel or more across a pixel. A wall at a depth of d metres along the view
// spans about d / screenScale metres a pixel where it faces the camera, and more where it does
// not, so beyond a depth of kWallMeanCyclesPerPixel times the bay's larger side times
// screenScale every pixel of it shows the mean. A batch whose box lies wholly beyond that depth
// is shaded with the mean per vertex (volume.vert's VOLUME_SHADING 3), as the plain shells are,
// and its fragments skip the texture: in the far overview that was a seventh of LOD0's pass
// (docs/BENCHMARKS.md, "LOD0's wall texture at its mean per vertex"). The shader takes these
// sizes from here ("wall_texture_sizes.glsl", in lodShaderLibrary), so the two cannot differ.
#pragma once

#include <glm/vec3.hpp>

#include <string>

namespace hexlod::lod {

inline constexpr float kWallBayMetres = 2.8f, kWallStoreyMetres = 3.0f; // the residential grammar's defaults
inline constexpr float kWallMeanCyclesPerPixel = 0.75f;                 // where the fade to the mean ends

// The sizes above as GLSL constants, for wall_texture.glsl.
std::string wallTextureSizesGlsl();

// Whether the box [lo, hi] (camera-relative metres) lies wholly beyond that depth along the
// view direction `forward` (unit length); `screenScale` is the pixels one metre spans at one
// metre's distance. False for NaN or non-positive inputs.
bool wallTextureIsMean(const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& forward, float screenScale);

} // namespace hexlod::lod
