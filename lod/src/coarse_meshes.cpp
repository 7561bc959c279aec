// Coarser meshes for the shapes whose generators have a coarser level.
#include "hexlod/lod/coarse_meshes.h"
#include "hexlod/render/mesh_deviation.h"
#include "hexlod/render/procedural_meshes.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <set>

namespace hexlod::lod {

std::vector<CoarseMesh> coarseMeshes(const cells::BatchCatalog& catalog,
                                     const render::TerminalMeshLibrary& meshes) {
    std::vector<CoarseMesh> coarse;
    std::map<const render::TerminalMesh*, CoarseMesh> byMesh; // mesh == null: none
    uint32_t base = 0;
    for (uint32_t g = 0; g < meshes.grammarCount(); base += uint32_t(meshes.shapeCount(g++))) {
        for (uint16_t s = 0; s < meshes.shapeCount(g); ++s) {
            const render::TerminalMesh& fine = meshes.mesh(g, s);
            auto [it, inserted] = byMesh.try_emplace(&fine);
            if (inserted) {
                std::optional<render::TerminalMesh> mesh =
                    render::buildCoarserProceduralMesh(catalog.grammar(g).grammar.shapes.at(s), fine);
                const glm::vec3 deviation = mesh ? render::meshDeviation(fine, *mesh) : glm::vec3(0.0f);
                // A level with nothing like some part of the mesh (a colour it dropped) would never
                // be small enough on screen: it is left out.
                if (mesh && std::isfinite(deviation.x + deviation.y + deviation.z)) {
                    it->second.deviation = deviation;
                    it->second.mesh = std::make_shared<const render::TerminalMesh>(std::move(*mesh));
                }
            }
            if (!it->second.mesh) continue;
            CoarseMesh entry = it->second;
            entry.shape = base + s;
            coarse.push_back(std::move(entry));
        }
    }
    return coarse;
}

std::string describeCoarseMeshes(std::span<const CoarseMesh> coarse, const ShapeTable& shapes) {
    std::string text;
    std::set<const render::TerminalMesh*> described;
    for (const CoarseMesh& entry : coarse) {
        if (!described.insert(entry.mesh.get()).second) continue;
        char line[160];
        std::snprintf(line, sizeof line, "%s %u -> %zu triangles (deviation u %.3f, v %.3f, t %.3f)",
                      entry.mesh->shape.c_str(), shapes.triangles(entry.shape), entry.mesh->triangleCount(),
                      entry.deviation.x, entry.deviation.y, entry.deviation.z);
        text += (text.empty() ? "coarse meshes: " : ", ") + std::string(line);
    }
    return text;
}

} // namespace hexlod::lod
