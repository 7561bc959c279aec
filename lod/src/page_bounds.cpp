// Page spheres: the bounding box of the terminals' sphere centres, then the farthest sphere.
#include "hexlod/lod/page_bounds.h"
#include "hexlod/lod/terminal_arena.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace hexlod::lod {
namespace {

// classifyTerminal's sphere of one terminal, relative to its cell origin.
glm::dvec4 terminalSphere(const grammar::TerminalRecord& record) {
    gpu::GpuTerminal t;
    std::memcpy(&t, &record, sizeof t);
    glm::vec3 axisX, axisY, axisZ;
    shared::terminalAxes(t, axisX, axisY, axisZ);
    const double width = shared::halfToFloat(t.size & 0xffffu), height = shared::halfToFloat(t.size >> 16);
    const double depth = shared::halfToFloat(t.shapeAndDepth >> 16) * std::min(width, height);
    const glm::dvec3 centre =
        glm::dvec3(t.position) + glm::dvec3(axisX) * (0.5 * width) + glm::dvec3(axisY) * (0.5 * height);
    return {centre, 0.5 * std::sqrt(width * width + height * height + 4.0 * depth * depth)};
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

} // namespace

std::vector<glm::vec4> pageSpheres(const grammar::TerminalSet& set) {
    const size_t records = set.records.size();
    std::vector<glm::vec4> spheres;
    spheres.reserve((records + kArenaPageRecords - 1) / kArenaPageRecords);
    glm::dvec4 terminal[kArenaPageRecords];
    for (size_t first = 0; first < records; first += kArenaPageRecords) {
        const size_t count = std::min<size_t>(kArenaPageRecords, records - first);
        glm::dvec3 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
        bool finite = true;
        for (size_t i = 0; i < count; ++i) {
            terminal[i] = terminalSphere(set.records[first + i]);
            finite = finite && std::isfinite(terminal[i].x) && std::isfinite(terminal[i].y) &&
                     std::isfinite(terminal[i].z) && std::isfinite(terminal[i].w);
            lo = glm::min(lo, glm::dvec3(terminal[i]));
            hi = glm::max(hi, glm::dvec3(terminal[i]));
        }
        const glm::dvec3 centre = 0.5 * (lo + hi);
        double radius = 0.0;
        for (size_t i = 0; i < count; ++i)
            radius = std::max(radius, glm::length(glm::dvec3(terminal[i]) - centre) + terminal[i].w);
        // Both tests run in float on camera-relative values: a centimetre plus a part in 1e5
        // of the page's size and place covers their rounding many times over.
        radius += 0.01 + 1e-5 * (radius + glm::length(centre));
        spheres.emplace_back(glm::vec3(centre),
                             finite ? float(radius) : std::numeric_limits<float>::infinity());
    }
    return spheres;
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

bool pageMayHoldLod4(const glm::vec4& sphere, const glm::vec3& origin, const shared::CullFrame& frame) {
    // No LOD distances (frame.lodDistance.w == 0): every visible terminal is LOD4.
    return frame.lodDistance.w == 0.0f || pageReachesWithin(sphere, origin, frame.lodDistance.x);
}

bool pageMayHoldLod3(const glm::vec4& sphere, const glm::vec3& origin, const shared::CullFrame& frame) {
    return frame.lodDistance.w != 0.0f && pageReachesWithin(sphere, origin, frame.lodDistance.y);
}

} // namespace hexlod::lod
