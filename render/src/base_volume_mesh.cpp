// Base volumes from extruded-set elements (base_volume_mesh.h).
#include "hexlod/render/base_volume_mesh.h"

#include "hexlod/render/polygon.h"
#include "mesh_builder.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace hexlod::render {
namespace {

constexpr uint32_t kWallColours[8] = {
    rgba8(150, 124, 96), rgba8(120, 60, 40),  rgba8(170, 160, 140), rgba8(90, 96, 104),
    rgba8(140, 110, 80), rgba8(110, 100, 90), rgba8(160, 140, 120), rgba8(70, 70, 75),
};
constexpr uint32_t kRoofColour = rgba8(60, 58, 56);

// Vertex ranges of the walls and the element each shows, to be written into the uv of the
// finished mesh (the builder's own uv projection runs in finish()).
struct WallTag {
    size_t firstVertex, vertexCount;
    uint32_t element;
};

// One storey band of a building: its faces in footprint-edge order. Returns the area and
// perimeter of its bottom ring, zero where the faces close no ring.
glm::vec2 band(MeshBuilder& b, const grammar::ExtrudedSet& set,
               std::vector<const grammar::ExtrudedElement*> faces, float inset, uint32_t wall,
               std::vector<WallTag>& tags) {
    std::sort(faces.begin(), faces.end(), [](const auto* l, const auto* r) { return l->atom < r->atom; });
    std::vector<glm::vec2> bottom, top;
    std::vector<float> bottomZ, topZ;
    for (const grammar::ExtrudedElement* e : faces) {
        const glm::vec3 up = e->origin + e->axisY * e->size.y;
        bottom.emplace_back(e->origin);
        top.emplace_back(up);
        bottomZ.push_back(e->origin.z);
        topZ.push_back(up.z);
    }
    if (signedArea2(bottom) <= 0.0 || signedArea2(top) <= 0.0) return glm::vec2(0.0f); // not a closed ring
    bottom = insetPolygon(bottom, inset);
    top = insetPolygon(top, inset);
    const size_t n = bottom.size();
    float perimeter = 0.0f;
    for (size_t i = 0; i < n; ++i) {
        const size_t j = (i + 1) % n;
        const glm::vec2 edge = bottom[j] - bottom[i];
        perimeter += glm::length(edge);
        const size_t before = b.vertexCount();
        b.quad({bottom[i], bottomZ[i]}, {bottom[j], bottomZ[j]}, {top[j], topZ[j]}, {top[i], topZ[i]},
               {edge.y, -edge.x, 0.0f}, wall);
        if (n == faces.size())
            tags.push_back({before, b.vertexCount() - before, uint32_t(faces[i] - set.elements.data())});
    }
    const std::vector<uint32_t> triangles = triangulatePolygon(top);
    for (size_t t = 0; t < triangles.size(); t += 3) {
        const glm::vec3 tri[3] = {{top[triangles[t]], topZ[triangles[t]]},
                                  {top[triangles[t + 1]], topZ[triangles[t + 1]]},
                                  {top[triangles[t + 2]], topZ[triangles[t + 2]]}};
        b.polygon(tri, {0, 0, 1}, kRoofColour);
    }
    return glm::vec2(float(0.5 * signedArea2(bottom)), perimeter);
}

} // namespace

uint32_t wallMaterialColour(uint16_t material) {
    return kWallColours[material % 8];
}

uint32_t roofColour() {
    return kRoofColour;
}

TerminalMesh buildBaseVolumes(const grammar::ExtrudedSet& set, float inset,
                              std::vector<VolumeBuilding>* buildings) {
    MeshBuilder b(glm::vec3(1.0f)); // metres stay metres
    std::vector<WallTag> tags;
    std::vector<std::pair<size_t, size_t>> vertexRanges; // per entry of *buildings
    if (buildings) buildings->clear();
    for (const grammar::ExtrudedBuilding& building : set.buildings) {
        const size_t firstTriangle = b.triangleCount(), firstVertex = b.vertexCount();
        // Bands keyed by stop rule and elevation in millimetres.
        std::map<std::pair<uint32_t, long long>, std::vector<const grammar::ExtrudedElement*>> bands;
        for (uint32_t i = 0; i < building.elementCount; ++i) {
            const grammar::ExtrudedElement& e = set.elements.at(building.firstElement + i);
            if (!(e.size.y > 0.0f) || !(e.size.x > 0.0f) || !std::isfinite(e.origin.z)) continue;
            bands[{e.rule, std::llround(double(e.origin.z) * 1000.0)}].push_back(&e);
        }
        const uint32_t wall = wallMaterialColour(building.wallMaterial);
        // The lowest closed band's footprint, for the building's point form.
        glm::vec2 footprint(0.0f);
        long long lowest = 0;
        for (auto& [key, faces] : bands) {
            if (faces.size() < 3) continue;
            const glm::vec2 ring = band(b, set, std::move(faces), inset, wall, tags);
            if (ring.x > 0.0f && (footprint.x == 0.0f || key.second < lowest))
                footprint = ring, lowest = key.second;
        }
        if (buildings && b.triangleCount() > firstTriangle) {
            VolumeBuilding part;
            part.firstIndex = uint32_t(3 * firstTriangle);
            part.indexCount = uint32_t(3 * (b.triangleCount() - firstTriangle));
            part.footprintArea = footprint.x;
            part.footprintPerimeter = footprint.y;
            part.wallColour = wall;
            buildings->push_back(part);
            vertexRanges.emplace_back(firstVertex, b.vertexCount());
        }
    }
    TerminalMesh mesh = b.finish("base_volume", "extruded set");
    for (size_t i = 0; i < vertexRanges.size(); ++i) {
        const auto& [first, end] = vertexRanges[i];
        vertexBounds(std::span(mesh.vertices).subspan(first, end - first), (*buildings)[i].boundsMin,
                     (*buildings)[i].boundsMax);
    }
    // uv: (element index, 1) on walls, (-1, 0) elsewhere (caps): LOD1 resumes the grammar of
    // the element a wall pixel shows.
    for (MeshVertex& v : mesh.vertices) v.uv = glm::vec2(-1.0f, 0.0f);
    for (const WallTag& tag : tags)
        for (size_t k = 0; k < tag.vertexCount; ++k)
            mesh.vertices[tag.firstVertex + k].uv = glm::vec2(float(tag.element), 1.0f);
    return mesh;
}

} // namespace hexlod::render
