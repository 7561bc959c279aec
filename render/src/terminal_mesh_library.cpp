// The terminal mesh library (terminal_mesh_library.h).
#include "hexlod/render/terminal_mesh_library.h"

#include "hexlod/render/gltf_mesh_loader.h"
#include "hexlod/render/procedural_meshes.h"

#include <cmath>
#include <map>
#include <set>
#include <tuple>

namespace hexlod::render {
namespace {

// Two declarations that would build the same mesh.
using DeclarationKey = std::tuple<std::string, float, float, float, uint32_t>;

bool usableSize(const grammar::ShapeInfo& s) {
    return std::isfinite(s.width) && std::isfinite(s.height) && std::isfinite(s.depthRatio) &&
           s.width > 0.0f && s.height > 0.0f && s.depthRatio >= 0.0f;
}

} // namespace

TerminalMeshLibrary::TerminalMeshLibrary(std::span<const grammar::CompiledGrammar* const> grammars,
                                         std::span<const GltfShapeSource> gltf) {
    std::map<DeclarationKey, std::shared_ptr<const TerminalMesh>> built;
    std::set<std::string> declared;
    meshes_.resize(grammars.size());
    for (size_t g = 0; g < grammars.size(); ++g) {
        for (const grammar::ShapeInfo& shape : grammars[g]->shapes) {
            declared.insert(shape.name);
            const DeclarationKey key{shape.name, shape.width, shape.height, shape.depthRatio,
                                     shape.triangles};
            auto& slot = built[key];
            if (!slot) {
                const std::string who = "shape '" + shape.name + "' (grammar " + grammars[g]->name + ")";
                std::optional<TerminalMesh> mesh;
                for (const GltfShapeSource& source : gltf) {
                    if (source.shape != shape.name || mesh) continue;
                    GltfLoadResult loaded =
                        loadGltfMesh(source.path, shape.name,
                                     nominalShapeSize(shape.width, shape.height, shape.depthRatio));
                    for (const std::string& warning : loaded.warnings) notes_.push_back(who + ": " + warning);
                    if (loaded.ok)
                        mesh = std::move(loaded.mesh);
                    else
                        notes_.push_back(who + ": " + loaded.error + "; using its procedural mesh instead");
                }
                if (!mesh && usableSize(shape)) mesh = buildProceduralMesh(shape);
                if (!mesh) {
                    grammar::ShapeInfo safe = shape;
                    if (!usableSize(shape)) safe.width = safe.height = 1.0f, safe.depthRatio = 0.0f;
                    mesh = buildFallbackMesh(safe);
                    ++fallbacks_;
                    notes_.push_back(who +
                                     ": no procedural generator and no glTF mesh; drawn as a magenta box");
                }
                slot = std::make_shared<const TerminalMesh>(std::move(*mesh));
                distinct_.push_back(slot);
            }
            meshes_[g].push_back(slot);
        }
    }
    for (const GltfShapeSource& source : gltf) {
        if (!declared.count(source.shape))
            notes_.push_back("shapes." + source.shape + ": no grammar of the scene declares this shape; " +
                             source.path + " is not used");
    }
}

const TerminalMesh* TerminalMeshLibrary::find(uint32_t grammar, uint16_t shape) const {
    if (grammar >= meshes_.size() || shape >= meshes_[grammar].size()) return nullptr;
    return meshes_[grammar][shape].get();
}

size_t TerminalMeshLibrary::byteSize() const {
    size_t bytes = 0;
    for (const auto& mesh : distinct_) bytes += mesh->byteSize();
    return bytes;
}

} // namespace hexlod::render
