// Frame constants, the pages to cull and the draw-list layout for the cull pass.
#include "hexlod/lod/cull_inputs.h"
#include "hexlod/lod/occlusion_tests.h"
#include "hexlod/lod/page_bounds.h"
#include "hexlod/lod/terminal_arena.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace hexlod::lod {

double screenScale(double fovY, uint32_t viewportHeight) {
    return 0.5 * double(viewportHeight) / std::tan(0.5 * fovY);
}

double lodDistance(double geometricError, const scene::LodProfile& profile, double fovY,
                   uint32_t viewportHeight) {
    return geometricError * screenScale(fovY, viewportHeight) / profile.maxScreenSpaceError;
}

shared::CullFrame makeCullFrame(const cells::Frustum& frustum, const scene::LodProfile& profile, double fovY,
                                uint32_t viewportHeight, double transitionBand, bool impostors) {
    shared::CullFrame frame{};
    const auto& planes = frustum.planes();
    for (size_t i = 0; i < 6; ++i) {
        frame.planes[i] = glm::vec4(glm::vec3(planes[i].normal), float(planes[i].offset));
    }
    const double lod3 = lodDistance(profile.geometricError[3], profile, fovY, viewportHeight);
    const double lod2 = lodDistance(profile.geometricError[2], profile, fovY, viewportHeight);
    frame.lodDistance =
        glm::vec4(float(lod3 * lod3), float(lod2 * lod2), float(transitionBand), impostors ? 1.0f : 0.0f);
    frame.trees = glm::vec4(-1.0f, 0.0f, 0.0f, 0.0f);
    return frame;
}

void setCoarseMeshes(shared::CullFrame& frame, const scene::LodProfile& profile, double fovY,
                     uint32_t viewportHeight) {
    // lodDistance of a unit error: the distance per metre of deviation.
    const double perMetre = lodDistance(1.0, profile, fovY, viewportHeight);
    frame.coarseMeshes = glm::vec4(float(perMetre * perMetre), 0.0f, 0.0f, 0.0f);
}

void setTreeCut(shared::CullFrame& frame, double billboardDistance, const glm::dvec3& treeOrigin,
                const glm::dvec3& camera) {
    const float cut = billboardDistance < 0.0 ? -1.0f : float(billboardDistance * billboardDistance);
    frame.trees = glm::vec4(cut, glm::vec3(treeOrigin - camera));
}

void setOcclusion(shared::CullFrame& frame, const glm::dvec3& forward, const glm::dvec3& up, double fovY,
                  double nearPlane, double farPlane, uint32_t width, uint32_t height, uint32_t columns,
                  uint32_t rows, uint32_t tilePixels) {
    const glm::dvec3 f = glm::normalize(forward);
    const glm::dvec3 right = glm::normalize(glm::cross(f, up));
    const glm::dvec3 cameraUp = glm::cross(right, f);
    const double scaleY = 1.0 / std::tan(0.5 * fovY), scaleX = scaleY * double(height) / double(width);
    frame.viewRight = glm::vec4(glm::vec3(right), float(scaleX));
    frame.viewUp = glm::vec4(glm::vec3(cameraUp), float(scaleY));
    frame.viewForward = glm::vec4(glm::vec3(f), float(nearPlane));
    // The reversed-Z projection of the renderer: depth(d) = n f / ((f - n) d) - n / (f - n).
    frame.depthMap = glm::vec4(float(nearPlane * farPlane / (farPlane - nearPlane)),
                               float(nearPlane / (farPlane - nearPlane)), float(width), float(height));
    frame.occlusion = glm::vec4(float(columns), float(rows), float(tilePixels), 0.0f);
}

namespace {

// Whether shape `s` has a coarse shape that fills lists of its own (DrawListLayout): `s` has an
// impostor, whose entries already take the back of its lists.
bool hasCoarseListsOfItsOwn(const CullInputs& inputs, uint32_t s) {
    return inputs.shapeCoarse[s].w >= 0.0f && inputs.shapeImpostor.at(s);
}

// A set's records by shape (they are sorted by shape), read in increasing record order.
class ShapeRuns {
public:
    ShapeRuns(const std::vector<uint32_t>& perShape, uint32_t records)
        : perShape_(&perShape), records_(records), end_(perShape.empty() ? records : perShape[0]) {}

    // How many records from `record` on, up to `last` (exclusive), share its shape, which
    // shape() then names; `record` is not less than the last call's.
    uint32_t from(uint32_t record, uint32_t last) {
        while (record >= end_ && shape_ + 1 < perShape_->size()) end_ += (*perShape_)[++shape_];
        if (record >= end_) end_ = records_; // counts short of the records: the last shape
        return std::min(end_, last) - record;
    }
    uint32_t shape() const { return shape_; }

private:
    const std::vector<uint32_t>* perShape_;
    uint32_t records_, shape_ = 0, end_;
};

// True only when every record of the page [first, first + count) is a tree part whose tree is a
// billboard this frame (treeIsBillboard, which the pass tests first): the page's shapes are all
// tree shapes and every tree id it spans is beyond the cut. `runs` is a copy: the caller's
// walk goes on from where it was.
bool pageTreesAreBillboards(const CullInputs& inputs, const CullBatchInput& batch, const PageBounds& page,
                            ShapeRuns runs, uint32_t first, uint32_t count) {
    if (!inputs.trees || inputs.shapeTree.empty() || inputs.frame.trees.x < 0.0f) return false;
    for (uint32_t r = first; r < first + count;) {
        r += runs.from(r, first + count);
        if (!inputs.shapeTree[batch.shapeBase + runs.shape()]) return false;
    }
    // A page's ids lie close together (one tree's leaves, or the trunks of a row of trees);
    // a wider span is not worth testing id by id.
    if (page.lastBuilding >= inputs.trees->size() ||
        page.lastBuilding - page.firstBuilding >= kArenaPageRecords)
        return false;
    for (uint32_t id = page.firstBuilding; id <= page.lastBuilding; ++id)
        if (!shared::treeIsBillboard(glm::vec3((*inputs.trees)[id]), inputs.frame)) return false;
    return true;
}

enum class PageSkip { None, Outside, FacingAway, Billboards, Occluded };

// Why the pass may leave the page [first, first + count) out whole, if it may: the cheap tests
// first, the occlusion test (which reads tiles) last.
PageSkip pageSkip(const CullInputs& inputs, const CullBatchInput& batch, const PageBounds& page,
                  const glm::vec3& origin, const ShapeRuns& runs, uint32_t first, uint32_t count) {
    if (!pageMayBeVisible(page, origin, inputs.frame)) return PageSkip::Outside;
    // A tree's parts stand free: no wall hides them from behind.
    const bool trees = batch.shapeBase < inputs.shapeTree.size() && inputs.shapeTree[batch.shapeBase];
    if (!trees && pageFacesAway(page, origin)) return PageSkip::FacingAway;
    if (pageTreesAreBillboards(inputs, batch, page, runs, first, count)) return PageSkip::Billboards;
    const glm::vec4& sphere = page.sphere;
    if (std::isfinite(sphere.w) &&
        tilesHideSphere(inputs.frame, inputs.occlusionTiles, glm::vec4(glm::vec3(sphere) + origin, sphere.w),
                        HEXLOD_OCCLUSION_MAX_TILES))
        return PageSkip::Occluded;
    return PageSkip::None;
}

} // namespace

CullPages selectCullPages(const CullInputs& inputs) {
    CullPages out;
    DrawListLayout& layout = out.layout;
    layout.base.assign(inputs.shapeCount, 0);
    layout.capacity.assign(inputs.shapeCount, 0);
    layout.lod3Capacity.assign(inputs.shapeCount, 0);
    // Per shape, its terminals in the pages that may hold LOD4 entries of a shape with an
    // impostor: the capacity of its coarse shape's own lists.
    std::vector<uint32_t> withinLod4(inputs.shapeCount, 0);
    for (uint32_t b = 0; b < inputs.batches.size(); ++b) {
        const CullBatchInput& batch = inputs.batches[b];
        const uint32_t records = uint32_t(batch.set->records.size());
        const glm::vec3 origin(batch.cellOrigin - inputs.camera); // as the pass receives it
        // Records are sorted by shape: walk the shapes' ranges alongside the pages.
        ShapeRuns runs(batch.set->countPerShape, records);
        for (uint32_t page = 0, first = 0; first < records; ++page, first += kArenaPageRecords) {
            const uint32_t count = std::min(kArenaPageRecords, records - first);
            const PageBounds* bounds = batch.pageBounds ? &(*batch.pageBounds)[page] : nullptr;
            const PageSkip skip =
                bounds ? pageSkip(inputs, batch, *bounds, origin, runs, first, count) : PageSkip::None;
            if (skip != PageSkip::None) {
                out.skippedTerminals += count;
                out.occludedTerminals += skip == PageSkip::Occluded ? count : 0;
                out.facingAwayTerminals += skip == PageSkip::FacingAway ? count : 0;
                out.billboardTerminals += skip == PageSkip::Billboards ? count : 0;
                continue;
            }
            out.pages.emplace_back(b, batch.pages ? (*batch.pages)[page] : first, count, 0u);
            out.terminals += count;
            const bool lod4 = !bounds || pageMayHoldLod4(bounds->sphere, origin, inputs.frame);
            const bool lod3 = !bounds || pageMayHoldLod3(bounds->sphere, origin, inputs.frame);
            for (uint32_t r = first; r < first + count;) {
                const uint32_t run = runs.from(r, first + count);
                const uint32_t shape = batch.shapeBase + runs.shape();
                layout.capacity[shape] += run;
                if (lod4) withinLod4[shape] += run;
                if (lod3 && inputs.shapeImpostor[shape]) layout.lod3Capacity[shape] += run;
                r += run;
            }
        }
    }
    // A coarse shape has no records of its own; each terminal of the shape it serves is drawn
    // with one of the two meshes. Where that shape has no impostor, the coarse entries fill
    // its lists from the back, where impostor entries would go. Where it has one, they get
    // lists of their own, as long as the served shape's terminals within LOD4's distance, when
    // they fit beside every shape's own.
    uint64_t records = std::accumulate(layout.capacity.begin(), layout.capacity.end(), uint64_t(0));
    for (uint32_t s = 0; s < inputs.shapeCoarse.size(); ++s)
        if (hasCoarseListsOfItsOwn(inputs, s)) records += withinLod4[s];
    if (records <= inputs.maxListRecords)
        for (uint32_t s = 0; s < inputs.shapeCoarse.size(); ++s)
            if (hasCoarseListsOfItsOwn(inputs, s))
                layout.capacity.at(uint32_t(inputs.shapeCoarse[s].w)) = withinLod4[s];
    layout.lod3Base.assign(inputs.shapeCount, 0);
    for (uint32_t s = 0; s < inputs.shapeCount; ++s) {
        layout.base[s] = uint32_t(layout.total);
        layout.total += layout.capacity[s];
        layout.lod3Base[s] = uint32_t(layout.lod3Total);
        layout.lod3Total += layout.lod3Capacity[s];
    }
    for (uint32_t s = 0; s < inputs.shapeCoarse.size(); ++s) {
        if (inputs.shapeCoarse[s].w < 0.0f || hasCoarseListsOfItsOwn(inputs, s)) continue;
        const uint32_t coarse = uint32_t(inputs.shapeCoarse[s].w);
        layout.base.at(coarse) = layout.base[s];
        layout.capacity.at(coarse) = layout.capacity[s];
    }
    return out;
}

std::vector<glm::vec4> coarseTable(const CullInputs& inputs, const DrawListLayout& layout) {
    std::vector<glm::vec4> table = inputs.shapeCoarse;
    for (uint32_t s = 0; s < table.size(); ++s)
        if (hasCoarseListsOfItsOwn(inputs, s) && layout.capacity.at(uint32_t(table[s].w)) == 0)
            table[s].w = -1.0f;
    return table;
}

} // namespace hexlod::lod
