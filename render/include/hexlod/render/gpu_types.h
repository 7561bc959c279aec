// Structs shared by C++ and GLSL, as niagara's mesh.h: the same file is included by the
// renderer's C++ and, through ShaderLibrary's #include, by its shaders. Keep to types and
// layouts both languages read alike (std430 for buffers, std140 for uniform blocks).
#ifdef __cplusplus
#pragma once
#include <glm/glm.hpp>

#include <cstdint>

namespace hexlod::gpu {
using uint = uint32_t;
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using uvec2 = glm::uvec2;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
#endif

// One terminal, byte for byte grammar::TerminalRecord (std430, 32 bytes): position relative
// to its cell origin (or, in the draw lists the cull pass writes, to the camera), building id,
// orientation quaternion as 4 x snorm16, width and height as 2 x half, shape id in the low
// 16 bits and depth ratio as a half in the high 16.
struct GpuTerminal {
    vec3 position;
    uint building;
    uvec2 orientation;
    uint size;
    uint shapeAndDepth;
};

// Vertex attribute locations of MeshVertex (render/terminal_mesh.h), of the back side's colour
// of LOD4's meshes (lod/shape_geometry.h) and of the per-instance terminal attributes that
// LOD4 draws read from a draw list.
#define HEXLOD_ATTRIBUTE_POSITION 0
#define HEXLOD_ATTRIBUTE_NORMAL 1
#define HEXLOD_ATTRIBUTE_UV 2
#define HEXLOD_ATTRIBUTE_COLOR 3
#define HEXLOD_ATTRIBUTE_INSTANCE_POSITION 4
#define HEXLOD_ATTRIBUTE_INSTANCE_BUILDING 5
#define HEXLOD_ATTRIBUTE_INSTANCE_ORIENTATION 6
#define HEXLOD_ATTRIBUTE_INSTANCE_SIZE 7
#define HEXLOD_ATTRIBUTE_BACK_COLOR 8
#define HEXLOD_ATTRIBUTE_INSTANCE_DEPTH 9
// A base volume vertex's extruded-set element (lod/volume_vertex.h).
#define HEXLOD_ATTRIBUTE_ELEMENT 10

#ifdef __cplusplus
static_assert(sizeof(GpuTerminal) == 32);
} // namespace hexlod::gpu
#endif
