// The generator registry: finds a shape's generator by name and picks its detail level by the
// grammar's triangle declaration (procedural_meshes.h).
#include "hexlod/render/procedural_meshes.h"

#include "hexlod/grammar/position_hash.h"
#include "shape_generators.h"

#include <algorithm>
#include <cstdlib>

namespace hexlod::render {
namespace {

const ShapeGenerator* findGenerator(const std::string& name) {
    for (const auto families = {windowGenerators(), facadeGenerators(), towerGenerators(), roofGenerators(),
                                treeGenerators()};
         const std::span<const ShapeGenerator> family : families) {
        for (const ShapeGenerator& g : family) {
            if (name == g.name) return &g;
        }
    }
    return nullptr;
}

} // namespace

float detailJitter(uint32_t a, uint32_t b) {
    return grammar::unitFloat(grammar::combineKey(grammar::mixBits(a), b));
}

std::vector<std::string> proceduralShapeNames() {
    std::vector<std::string> names;
    for (const auto families = {windowGenerators(), facadeGenerators(), towerGenerators(), roofGenerators(),
                                treeGenerators()};
         const std::span<const ShapeGenerator> family : families) {
        for (const ShapeGenerator& g : family) names.emplace_back(g.name);
    }
    std::sort(names.begin(), names.end());
    return names;
}

std::optional<TerminalMesh> buildProceduralMesh(const grammar::ShapeInfo& shape) {
    const ShapeGenerator* generator = findGenerator(shape.name);
    if (!generator) return std::nullopt;
    const glm::vec3 nominal = nominalShapeSize(shape.width, shape.height, shape.depthRatio);
    std::optional<MeshBuilder> best;
    for (int detail = 0; detail <= generator->maxDetail; ++detail) {
        MeshBuilder candidate(nominal);
        generator->build(candidate, detail);
        const auto miss = [&](const MeshBuilder& b) {
            return std::llabs(static_cast<long long>(b.triangleCount()) -
                              static_cast<long long>(shape.triangles));
        };
        if (!best || miss(candidate) < miss(*best)) best = std::move(candidate);
    }
    return best->finish(shape.name, "procedural");
}

TerminalMesh buildFallbackMesh(const grammar::ShapeInfo& shape) {
    const glm::vec3 nominal = nominalShapeSize(shape.width, shape.height, shape.depthRatio);
    MeshBuilder b(nominal);
    if (nominal.z > 0.0f)
        b.box(glm::vec3(0.0f), nominal, palette::kFallback);
    else
        b.quad({0, 0, 0}, {b.W(), 0, 0}, {b.W(), b.H(), 0}, {0, b.H(), 0}, {0, 0, 1}, palette::kFallback);
    return b.finish(shape.name, "fallback");
}

} // namespace hexlod::render
