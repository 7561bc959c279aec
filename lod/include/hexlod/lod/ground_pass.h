// The ground under the city: a plane around the camera, far enough to meet the fog, and the
// scene's streets on it, so a walkthrough sees pavement between the buildings instead of sky.
#pragma once

#include "hexlod/render/shader_program.h"
#include "hexlod/scene/city_generator.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>

namespace hexlod::lod {

class GroundPass {
public:
    GroundPass() = default;
    ~GroundPass();
    GroundPass(const GroundPass&) = delete;
    GroundPass& operator=(const GroundPass&) = delete;

    // Street quads relative to `origin` (any point near the city; precision is relative to it).
    void upload(std::span<const scene::RoadSegment> roads, const glm::dvec3& origin);
    // Draws with `program` (volume.vert/volume.frag shaded per pixel, VOLUME_SHADING 1: the
    // plane is one rectangle out to the fog; offset by cellOffset).
    // Returns the triangles drawn.
    uint64_t draw(const render::ShaderProgram& program, const glm::dvec3& camera) const;
    uint64_t byteSize() const { return bytes_; }
    const glm::dvec3& origin() const { return origin_; }

private:
    uint32_t groundVao_ = 0, roadVao_ = 0, buffers_[4] = {0, 0, 0, 0};
    uint32_t roadIndices_ = 0;
    glm::dvec3 origin_{0.0};
    uint64_t bytes_ = 0;
};

} // namespace hexlod::lod
