// The generator registry: finds a shape's generator by name and picks its detail level by the
// grammar's triangle declaration (procedural_meshes.h).
#include "hexlod/render/procedural_meshes.h"

#include "hexlod/grammar/position_hash.h"
#include "shape_generators.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>

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
    // Every generator's triangle count grows with its detail level (a test holds them to it),
    // so the closest level is the first that reaches the declaration or the one before it.
    // A linear guess from levels 0 and 1 starts the walk, so few levels are ever built.
    std::map<int, MeshBuilder> built;
    const auto at = [&](int detail) -> const MeshBuilder& {
        auto it = built.find(detail);
        if (it == built.end()) {
            it = built.emplace(detail, MeshBuilder(nominal)).first;
            generator->build(it->second, detail);
        }
        return it->second;
    };
    const auto count = [&](int detail) { return static_cast<long long>(at(detail).triangleCount()); };
    const long long target = shape.triangles;
    int detail = 0;
    if (generator->maxDetail > 0 && count(1) > count(0)) {
        const long long guess = (target - count(0)) / (count(1) - count(0));
        detail = static_cast<int>(std::clamp<long long>(guess, 0, generator->maxDetail));
    }
    while (detail < generator->maxDetail && count(detail) < target) ++detail;
    while (detail > 0 && count(detail - 1) >= target) --detail;
    if (detail > 0 && std::llabs(count(detail - 1) - target) <= std::llabs(count(detail) - target)) --detail;
    const MeshBuilder* best = &at(detail);
    return best->finish(shape.name, "procedural");
}

std::optional<TerminalMesh> buildCoarserProceduralMesh(const grammar::ShapeInfo& shape,
                                                       const TerminalMesh& fine) {
    const ShapeGenerator* generator = findGenerator(shape.name);
    if (fine.source != "procedural" || !generator) return std::nullopt;
    grammar::ShapeInfo coarser = shape;
    coarser.triangles = uint32_t(std::lround(generator->coarseShare * float(fine.triangleCount())));
    std::optional<TerminalMesh> mesh = buildProceduralMesh(coarser);
    if (!mesh || 4 * mesh->triangleCount() > 3 * fine.triangleCount()) return std::nullopt;
    return mesh;
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
