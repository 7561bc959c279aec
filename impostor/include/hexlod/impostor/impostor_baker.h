// Bakes impostor views by rendering geometry through render/ (thesis §7.3.1): for each view
// of the layout an orthographic image of the geometry's bounding sphere, into the view's tile.
// Needs a current GL context.
#pragma once

#include "hexlod/impostor/impostor_atlas.h"
#include "hexlod/render/framebuffer.h"
#include "hexlod/render/shader_program.h"
#include "hexlod/render/terminal_mesh.h"

#include <span>
#include <string>

namespace hexlod::impostor {

// Geometry in metric shape space (a terminal mesh at its nominal size, or a whole tree).
struct BakeGeometry {
    std::vector<render::MeshVertex> vertices;
    std::vector<uint32_t> indices;
    uint64_t hash = 0; // of what the geometry was made from; keys the bake
};

// A terminal mesh scaled from unit scope space to its nominal size (normals are already
// metric at that size, see terminal_mesh.h).
BakeGeometry geometryFromMesh(const render::TerminalMesh& mesh);

class ImpostorBaker {
public:
    // Samples per texel side: views are rendered at this multiple and averaged, so silhouettes
    // carry fractional coverage instead of stair steps.
    static constexpr uint32_t kSupersampling = 3;

    // Compiles the bake shaders; false with the reason when they do not build.
    bool init(std::string& error);

    // Renders every view of `layout` into `out` (its shape name is left to the caller),
    // supersampled (kSupersampling). Empty
    // texels are dilated from their covered neighbours within the tile, colour and normal
    // only, so filtering at a silhouette does not fade to black; their alpha stays 0.
    bool bake(const BakeGeometry& geometry, const ViewLayout& layout, ImpostorAtlas& out, std::string& error);

    // The image one view would hold for an arbitrary direction, without dilation: an
    // innerResolution^2 albedo and normal-depth pair framed like the atlas's views. Tests
    // compare reconstructions against it.
    bool renderDirection(const BakeGeometry& geometry, const ViewLayout& layout, const glm::vec3& direction,
                         render::Image& albedo, render::Image& normalDepth, std::string& error);

private:
    struct Upload;
    bool drawViews(const BakeGeometry& geometry, const ViewLayout& layout,
                   std::span<const glm::vec3> directions, uint32_t tileSize, uint32_t padding,
                   uint32_t columns, render::Image& albedo, render::Image& normalDepth, std::string& error);

    render::ShaderProgram program_;
};

// Bounds and bounding sphere of the geometry, as the baker frames it.
void measureGeometry(const BakeGeometry& geometry, ImpostorAtlas& atlas);

} // namespace hexlod::impostor
