// The frame's shader programs and texture units, shared by the files that implement
// CityRenderer.
#pragma once

#include "hexlod/lod/city_renderer.h"
#include "hexlod/render/shader_program.h"

#include <cstdint>
#include <map>

namespace hexlod::lod {

// The depth tiles' texture unit in the passes that test against them: past the impostor and
// tree passes' own textures (units 0 to 3).
inline constexpr uint32_t kDepthTilesUnit = 7;

struct CityRenderer::Programs {
    render::ShaderProgram lod4, impostor, impostorWall; // impostor: LOD3 ray-cast; impostorWall: LOD2
    // Base volumes: plain (the shells under terminal sets), textured (LOD0), LOD0 where its
    // texture is its mean (wall_texture_mean.h); the ground.
    render::ShaderProgram volume, texturedVolume, meanWallVolume, ground;
    render::ShaderProgram buildingPoint;            // LOD0's far buildings (building_points.h)
    std::map<uint32_t, render::ShaderProgram> lod1; // per building grammar with buildings
};

} // namespace hexlod::lod
