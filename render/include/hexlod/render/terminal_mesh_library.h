// The terminal mesh library: one mesh per (grammar, shape) that a scene's grammars declare,
// and no other. A shape takes its glTF file when the scene maps its name to one, else its
// procedural generator, else a magenta fallback box; every fallback and every glTF problem is
// a line in notes(), so the caller can log it. Shapes of the same name and declaration in
// several grammars share one mesh object.
//
// Use from the renderer: for a terminal set of grammar g, draw the records of shape s (the
// range TerminalSet::firstOfShape(s), countPerShape[s]) instanced with mesh(g, s), the scope
// transform and the normal rule of terminal_mesh.h.
#pragma once

#include "hexlod/grammar/compiled_grammar.h"
#include "hexlod/render/terminal_mesh.h"

#include <memory>
#include <span>
#include <string>
#include <vector>

namespace hexlod::render {

// A scene config's `shapes` entry (scene::ShapeSource), kept free of the scene module.
struct GltfShapeSource {
    std::string shape;
    std::string path;
};

class TerminalMeshLibrary {
public:
    TerminalMeshLibrary() = default;
    // `grammars` in the scene's order (building grammars, then tree grammars); null entries
    // are not allowed. Never throws for bad meshes: they become fallbacks with a note.
    TerminalMeshLibrary(std::span<const grammar::CompiledGrammar* const> grammars,
                        std::span<const GltfShapeSource> gltf = {});

    size_t grammarCount() const { return meshes_.size(); }
    size_t shapeCount(uint32_t grammar) const { return meshes_.at(grammar).size(); }
    // Throws std::out_of_range for an unknown grammar or shape.
    const TerminalMesh& mesh(uint32_t grammar, uint16_t shape) const {
        return *meshes_.at(grammar).at(shape);
    }
    // Null for an unknown grammar or shape.
    const TerminalMesh* find(uint32_t grammar, uint16_t shape) const;
    // The shared mesh object, for uploading each distinct mesh once.
    std::shared_ptr<const TerminalMesh> shared(uint32_t grammar, uint16_t shape) const {
        return meshes_.at(grammar).at(shape);
    }

    // Distinct mesh objects and their bytes (vertices + indices).
    size_t distinctMeshCount() const { return distinct_.size(); }
    size_t byteSize() const;
    // "shape 'x' (grammar 1): ..." lines: fallbacks, glTF errors and warnings, unused sources.
    const std::vector<std::string>& notes() const { return notes_; }
    size_t fallbackCount() const { return fallbacks_; }

private:
    std::vector<std::vector<std::shared_ptr<const TerminalMesh>>> meshes_;
    std::vector<std::shared_ptr<const TerminalMesh>> distinct_;
    std::vector<std::string> notes_;
    size_t fallbacks_ = 0;
};

} // namespace hexlod::render
