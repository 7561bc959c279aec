// Page bounds: a sphere and a box around the terminals' spheres, the walls the terminals face
// and the building ids they span.
#include "hexlod/lod/page_bounds.h"
#include "hexlod/lod/terminal_arena.h"

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace hexlod::lod {
namespace {

// classifyTerminal's sphere of one terminal, relative to its cell origin, and the two values
// its backface test reads: the normal its wall faces and dot(normal, corner) - depth.
struct TerminalBounds {
    glm::dvec4 sphere;
    glm::vec3 normal;
    double wallOffset;
};

TerminalBounds terminalBounds(const grammar::TerminalRecord& record) {
    gpu::GpuTerminal t;
    std::memcpy(&t, &record, sizeof t);
    glm::vec3 axisX, axisY, axisZ;
    shared::terminalAxes(t, axisX, axisY, axisZ);
    const float width = shared::halfToFloat(t.size & 0xffffu), height = shared::halfToFloat(t.size >> 16);
    // In float, as classifyTerminal computes it.
    const float depth = shared::halfToFloat(t.shapeAndDepth >> 16) * std::min(width, height);
    const glm::dvec3 centre =
        glm::dvec3(t.position) + glm::dvec3(axisX) * (0.5 * width) + glm::dvec3(axisY) * (0.5 * height);
    const double w = width, h = height, d = depth;
    return {glm::dvec4(centre, 0.5 * std::sqrt(w * w + h * h + 4.0 * d * d)), axisZ,
            glm::dot(glm::dvec3(axisZ), glm::dvec3(t.position)) - d};
}

// The page's sphere: the bounding box of the terminals' sphere centres, then the farthest
// sphere; and the box around the spheres.
void setSphereAndBox(const TerminalBounds* terminals, size_t count, PageBounds& page) {
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
    glm::dvec3 boxLo = lo, boxHi = hi;
    for (size_t i = 0; i < count; ++i) {
        const glm::dvec4& sphere = terminals[i].sphere;
        lo = glm::min(lo, glm::dvec3(sphere));
        hi = glm::max(hi, glm::dvec3(sphere));
        boxLo = glm::min(boxLo, glm::dvec3(sphere) - sphere.w);
        boxHi = glm::max(boxHi, glm::dvec3(sphere) + sphere.w);
    }
    const glm::dvec3 centre = 0.5 * (lo + hi);
    double radius = 0.0;
    for (size_t i = 0; i < count; ++i)
        radius =
            std::max(radius, glm::length(glm::dvec3(terminals[i].sphere) - centre) + terminals[i].sphere.w);
    // Both tests run in float on camera-relative values: a centimetre plus a part in 1e5 of the
    // page's size and place covers their rounding many times over.
    const double padding = 0.01 + 1e-5 * (radius + glm::length(centre));
    page.sphere = glm::vec4(glm::vec3(centre), float(radius + padding));
    page.boxMin = glm::vec3(boxLo - padding);
    page.boxMax = glm::vec3(boxHi + padding);
}

// The page's faces from its terminals: the normals exactly as classifyTerminal computes them,
// so that the terminals of one wall share one; each offset rounded down, so the test stays
// loose. None when the terminals face more walls than a page holds.
void setFaces(const TerminalBounds* terminals, size_t count, PageBounds& page) {
    double offsets[std::size(page.faces)];
    for (size_t i = 0; i < count; ++i) {
        uint32_t f = 0;
        while (f < page.faceCount && glm::vec3(page.faces[f]) != terminals[i].normal) ++f;
        if (f == std::size(page.faces)) {
            page.faceCount = 0;
            return;
        }
        if (f == page.faceCount) {
            page.faces[page.faceCount++] = glm::vec4(terminals[i].normal, 0.0f);
            offsets[f] = terminals[i].wallOffset;
        }
        offsets[f] = std::min(offsets[f], terminals[i].wallOffset);
    }
    for (uint32_t f = 0; f < page.faceCount; ++f) {
        page.faces[f].w = float(offsets[f]);
        if (double(page.faces[f].w) > offsets[f])
            page.faces[f].w = std::nextafter(page.faces[f].w, -INFINITY);
    }
}

// Whether some point of `sphere` lies nearer the camera than the square root of
// `distanceSquared`. classifyTerminal compares its sphere's centre, held by this sphere, in
// float: the same relative slack as pageMayBeVisible keeps this test the looser one.
bool pageReachesWithin(const glm::vec4& sphere, const glm::vec3& origin, float distanceSquared) {
    if (!(sphere.w < std::numeric_limits<float>::infinity())) return true;
    const float distance = glm::length(glm::vec3(sphere) + origin);
    const float nearest = distance - sphere.w - 1e-5f * distance;
    return nearest <= 0.0f || nearest * nearest < distanceSquared;
}

// One page: records [first, first + count).
PageBounds boundsOfPage(const grammar::TerminalSet& set, size_t first, size_t count) {
    TerminalBounds terminal[kArenaPageRecords];
    PageBounds page;
    bool finite = true;
    page.firstBuilding = page.lastBuilding = set.records[first].building;
    for (size_t i = 0; i < count; ++i) {
        const grammar::TerminalRecord& record = set.records[first + i];
        terminal[i] = terminalBounds(record);
        const glm::dvec4& sphere = terminal[i].sphere;
        finite = finite && std::isfinite(sphere.x) && std::isfinite(sphere.y) && std::isfinite(sphere.z) &&
                 std::isfinite(sphere.w) && std::isfinite(terminal[i].wallOffset);
        page.firstBuilding = std::min(page.firstBuilding, record.building);
        page.lastBuilding = std::max(page.lastBuilding, record.building);
    }
    setSphereAndBox(terminal, count, page);
    if (finite)
        setFaces(terminal, count, page);
    else
        page.sphere.w = std::numeric_limits<float>::infinity(); // never culled whole
    return page;
}

} // namespace

std::vector<PageBounds> pageBounds(const grammar::TerminalSet& set) {
    const size_t records = set.records.size();
    std::vector<PageBounds> pages((records + kArenaPageRecords - 1) / kArenaPageRecords);
    // Pages are independent. A frame uploads new sets before it draws, while the rasteriser's
    // threads are idle, so the pages are split across the cores (a large set is thousands).
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, pages.size(), 64), [&](const tbb::blocked_range<size_t>& range) {
            for (size_t p = range.begin(); p != range.end(); ++p) {
                const size_t first = p * kArenaPageRecords;
                pages[p] = boundsOfPage(set, first, std::min<size_t>(kArenaPageRecords, records - first));
            }
        });
    return pages;
}

bool pageMayBeVisible(const glm::vec4& sphere, const glm::vec3& origin, const shared::CullFrame& frame) {
    if (!(sphere.w < std::numeric_limits<float>::infinity())) return true;
    const glm::vec3 centre = glm::vec3(sphere) + origin;
    // The planes' distances grow with the distance from the camera, and so does float error.
    const float slack = 1e-5f * glm::length(centre);
    for (const glm::vec4& plane : frame.planes)
        if (glm::dot(glm::vec3(plane), centre) + plane.w < -(sphere.w + slack)) return false;
    return true;
}

bool pageMayBeVisible(const PageBounds& page, const glm::vec3& origin, const shared::CullFrame& frame) {
    if (!pageMayBeVisible(page.sphere, origin, frame)) return false;
    if (!(page.sphere.w < std::numeric_limits<float>::infinity())) return true;
    // The box is outside a plane when its corner farthest along the plane's (unit) normal is;
    // each terminal's sphere lies within it. The same slack as the sphere's.
    const float slack = 1e-5f * (glm::length(glm::vec3(page.sphere) + origin) + page.sphere.w);
    for (const glm::vec4& plane : frame.planes) {
        const glm::vec3 corner(plane.x >= 0.0f ? page.boxMax.x : page.boxMin.x,
                               plane.y >= 0.0f ? page.boxMax.y : page.boxMin.y,
                               plane.z >= 0.0f ? page.boxMax.z : page.boxMin.z);
        if (glm::dot(glm::vec3(plane), corner + origin) + plane.w < -slack) return false;
    }
    return true;
}

bool pageFacesAway(const PageBounds& page, const glm::vec3& origin) {
    if (page.faceCount == 0) return false;
    // classifyTerminal reads the corner as position + origin in float, and the normal as the GPU
    // rounds it: a centimetre plus a part in 1e5 of the distances involved covers both, as the
    // sphere's padding does.
    const double slack = 0.01 + 1e-5 * (glm::length(glm::dvec3(origin)) +
                                        glm::length(glm::dvec3(page.sphere)) + page.sphere.w);
    for (uint32_t f = 0; f < page.faceCount; ++f) {
        const glm::vec4& face = page.faces[f];
        if (!(double(face.w) + glm::dot(glm::dvec3(face), glm::dvec3(origin)) > slack)) return false;
    }
    return true;
}

bool pageMayHoldLod4(const glm::vec4& sphere, const glm::vec3& origin, const shared::CullFrame& frame) {
    // No LOD distances (frame.lodDistance.w == 0): every visible terminal is LOD4.
    return frame.lodDistance.w == 0.0f || pageReachesWithin(sphere, origin, frame.lodDistance.x);
}

bool pageMayHoldLod3(const glm::vec4& sphere, const glm::vec3& origin, const shared::CullFrame& frame) {
    return frame.lodDistance.w != 0.0f && pageReachesWithin(sphere, origin, frame.lodDistance.y);
}

} // namespace hexlod::lod
