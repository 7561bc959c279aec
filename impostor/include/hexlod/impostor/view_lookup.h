// "Which views show this direction, and how much of each": a FLANN kd-tree over a layout's
// view directions answers it for LOD3's four-view blend, and a precomputed table answers it
// on the GPU.
//
// Weights. With d1 <= ... <= d5 the distances to the five nearest views, view i of the four
// nearest gets the share 1/di - 1/d5 of their sum, less kMinViewShare, normalised to sum 1.
// The fourth weight reaches 0 exactly when the fifth view takes its place, so the weights are
// continuous over the sphere; a direction on a view gives that view weight 1. With fewer than
// five views (a 2 x 2 grid) every view takes part and plain inverse distances are used. The
// floor drops the views whose share is small: they blur the blend with views far from the
// direction, and each costs LOD3 and the tree billboards its texture reads per pixel
// (docs/BENCHMARKS.md, "LOD3 and the billboards blend the views that matter"). Weights come
// largest first, so the views that take part come first; the GPU's loop ends at the first
// zero.
#pragma once

#include "hexlod/impostor/view_layout.h"

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace hexlod::impostor {

// A view's share of the blend under which it drops out (see above).
inline constexpr float kMinViewShare = 0.2f;
static_assert(kMinViewShare < 0.25f, "the nearest of four views has a share of at least a quarter");

// Texels per side of the GPU's tables: LOD3's facade impostors, the tree species' billboards.
// The web viewer builds its tables at the same sizes (web/src/render/view_table.js).
inline constexpr uint32_t kFacadeTableResolution = 128;
inline constexpr uint32_t kSpeciesTableResolution = 64;

struct ViewWeights {
    std::array<uint32_t, 4> views{}; // view indices, nearest first
    std::array<float, 4> weights{};  // sum to 1, largest first; 0 past `count`
    uint32_t count = 0;              // views with a weight above 0 (1 to 4)
};

// The GPU's lookup: a square of `resolution`^2 texels over the layout's (hemi-)octahedral
// square; texel (x, y) holds the blend for the direction at its centre.
struct DirectionTable {
    uint32_t resolution = 0;
    ViewSphere sphere = ViewSphere::Hemisphere;
    std::vector<ViewWeights> texels; // row-major

    // The texel the GPU reads for `direction` (nearest, as impostorViews() in GLSL does).
    const ViewWeights& at(const glm::vec3& direction) const;
};

class ViewLookup {
public:
    explicit ViewLookup(const ViewLayout& layout);
    ~ViewLookup();
    ViewLookup(ViewLookup&&) noexcept;
    ViewLookup& operator=(ViewLookup&&) noexcept;

    const ViewLayout& layout() const { return layout_; }

    // The blend for `direction` (shape space, toward the viewer; need not be unit length). For
    // a hemisphere layout a direction behind the wall is pulled onto the rim (straight behind
    // gives the front view). False for a NaN, infinite or zero direction.
    bool nearestViews(const glm::vec3& direction, ViewWeights& out) const;

    // Throws std::invalid_argument for a resolution of 0 or above 1024.
    DirectionTable buildTable(uint32_t resolution) const;

private:
    struct Index;
    ViewLayout layout_;
    std::vector<float> directions_; // 3 floats per view
    std::unique_ptr<Index> index_;
};

} // namespace hexlod::impostor
