// Rebuilding a shape's image for any direction from its baked views (LOD3): the four nearest
// views, each sampled where the surface the output pixel sees lies in that view, found by
// iterating on the stored depth (parallax correction), then blended by the lookup's weights
// over coverage. The GLSL version (impostor_views.glsl) follows the same steps; tests hold
// the two together.
#pragma once

#include "hexlod/impostor/impostor_atlas.h"
#include "hexlod/impostor/view_lookup.h"

namespace hexlod::impostor {

struct ReconstructionOptions {
    uint32_t parallaxIterations = 3; // 0: sample every view at the pixel's own position
    bool centralViewOnly = false;    // LOD2: the nearest view alone, no blend
};

struct Reconstruction {
    render::Image albedo;      // RGBA, alpha = blended coverage
    render::Image normalDepth; // xyz normal (unit where covered), w depth
};

// The image of `direction` (shape space, toward the viewer), framed like the atlas's views'
// inner area, `resolution` texels square. False for a direction the lookup rejects.
bool reconstructView(const ImpostorAtlas& atlas, const ViewLookup& lookup, const glm::vec3& direction,
                     uint32_t resolution, const ReconstructionOptions& options, Reconstruction& out);

// The same with the blend given, e.g. a DirectionTable's texel, as the GPU reads it.
bool reconstructView(const ImpostorAtlas& atlas, ViewWeights weights, const glm::vec3& direction,
                     uint32_t resolution, const ReconstructionOptions& options, Reconstruction& out);

// Bilinear sample of a view's tile at view coordinates (u, v) in [-1, 1] (clamped to the
// tile's inner area, so a tile never reads its neighbours). Four channels.
glm::vec4 sampleView(const render::Image& image, const ViewLayout& layout, uint32_t view, glm::vec2 uv);

} // namespace hexlod::impostor
