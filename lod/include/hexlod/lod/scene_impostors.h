// Baking a scene's impostors (ARCHITECTURE.md §4): every terminal shape its building grammars
// can emit (grammar::emittedShapes) for the grammars that have buildings, on the facade layout,
// and one full-sphere impostor per tree species that has trees, and nothing else. Each bake
// goes through the content-addressed store when one is given, so an unchanged shape is loaded,
// not rebaked. Needs a current GL context.
#pragma once

#include "hexlod/impostor/impostor_baker.h"
#include "hexlod/impostor/impostor_store.h"
#include "hexlod/render/terminal_mesh_library.h"
#include "hexlod/scene/scene_builder.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace hexlod::lod {

struct SceneImpostorOptions {
    impostor::ViewLayout facadeLayout; // hemisphere, for terminal shapes
    impostor::ViewLayout treeLayout{impostor::ViewSphere::FullSphere, 8, 128, 2}; // full sphere, for species
    std::string storeDirectory; // empty: bake everything, store nothing
    // Called after each shape with (done, total, name), for a progress bar.
    std::function<void(size_t, size_t, const std::string&)> progress;
};

enum class BakeOutcome : uint8_t { Baked, Loaded, Rebaked };

struct BakedShapeReport {
    std::string name;     // shape name, or "tree:<species>"
    uint32_t grammar = 0; // scene order: building grammars, then tree grammars
    int shape = -1;       // -1 for a tree species
    BakeOutcome outcome = BakeOutcome::Baked;
    std::string note; // why a file was rebaked
    double seconds = 0.0;
    uint64_t fileBytes = 0; // EXR bytes in the store (0 without one)
    uint64_t gpuBytes = 0;
};

struct SceneImpostorReport {
    std::vector<BakedShapeReport> shapes;
    uint32_t declaredShapes = 0; // over every grammar of the scene
    uint32_t skippedUnused = 0;  // declared but not emitted, or of a grammar without buildings
    uint32_t treeSpecies = 0;    // species impostors made
    double seconds = 0.0;
    uint64_t fileBytes = 0, gpuBytes = 0;
    // e.g. "impostors: 9 of 31 declared shapes baked (used by this scene)".
    std::string summary() const;
};

struct SceneImpostors {
    std::vector<impostor::ImpostorAtlas> facades;      // one per emitted shape of the facade layout
    std::vector<std::vector<int>> facadeLayer;         // [grammar][shape]: index into facades, -1 none
    std::vector<impostor::ImpostorAtlas> species;      // one per tree species with trees
    std::vector<std::vector<float>> speciesParameters; // the species' resolved parameters
    std::vector<uint32_t> speciesGrammar;              // its tree grammar, scene order
};

// False with a reason on a layout or GL failure; a shape whose bake fails (no triangles, say)
// is left without impostor and named in the report's note, not an error for the scene.
bool bakeSceneImpostors(const scene::BuiltScene& scene, const render::TerminalMeshLibrary& meshes,
                        const SceneImpostorOptions& options, SceneImpostors& out, SceneImpostorReport& report,
                        std::string& error);

// One tree species: the trees of a tree grammar whose parameters are exactly these values.
struct TreeSpeciesBake {
    const grammar::CompiledGrammar* grammar = nullptr;
    uint32_t grammarIndex = 0; // scene order: building grammars, then tree grammars
    std::vector<float> parameters;
    uint64_t seed = 0; // the scene's
    std::string name;  // of the atlas in the store: "tree:<species>"
};

// Bakes one species' impostor on `layout` (a full sphere), or loads it from `store` (null:
// none). bakeSceneImpostors bakes its species with it and the service the species that edits
// make, so a species' geometry and key are made in one place. Needs a current GL context and
// an initialised baker. False when the bake fails; `report.note` says why.
bool bakeTreeSpecies(impostor::ImpostorBaker& baker, const impostor::ImpostorStore* store,
                     const TreeSpeciesBake& species, const render::TerminalMeshLibrary& meshes,
                     const impostor::ViewLayout& layout, impostor::ImpostorAtlas& atlas,
                     BakedShapeReport& report);

// The geometry of one tree of a species: its terminal set expanded at the origin, every
// terminal's mesh placed in tree space (x east, y north, z up, the trunk base at the origin).
// A part whose shape has a coarser mesh (render::buildCoarserProceduralMesh) that moves no
// point of it by more than `sampleSpacing` metres (meshDeviation over the part's scope) is
// placed coarse: a bake whose samples lie that far apart cannot tell them apart, and the
// bake's time is its triangles. 0: every part at its full mesh.
impostor::BakeGeometry treeGeometry(const grammar::CompiledGrammar& grammar,
                                    const std::vector<float>& parameters, uint64_t seed,
                                    const render::TerminalMeshLibrary& meshes, uint32_t grammarIndex,
                                    float sampleSpacing = 0.0f);

} // namespace hexlod::lod
