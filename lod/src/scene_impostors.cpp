// Which impostors a scene needs, and baking or loading each once.
#include "hexlod/lod/scene_impostors.h"
#include "hexlod/grammar/expander.h"
#include "hexlod/grammar/rule_reachability.h"
#include "hexlod/render/mesh_deviation.h"
#include "hexlod/render/procedural_meshes.h"

#include <chrono>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>

namespace hexlod::lod {
namespace {

uint64_t hashBytes(uint64_t hash, const void* data, size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 0x100000001b3ull; // FNV-1a
    return hash;
}

struct BakeItem {
    std::string name;
    uint32_t grammar = 0;
    int shape = -1; // -1: a tree species
    const std::vector<float>* parameters = nullptr;
};

// A species' name from the config: the first species of the grammar whose parameters resolve
// to these values; the position among the grammar's species otherwise.
std::string speciesName(const scene::BuiltScene& scene, const scene::GrammarBuildings& trees,
                        const std::vector<float>& parameters, size_t ordinal) {
    for (const scene::TreeSpecies& species : scene.config.trees.species) {
        if (species.grammar != trees.name) continue;
        std::vector<grammar::ParameterOverride> overrides;
        for (const auto& [name, value] : species.params) overrides.push_back({name, value});
        grammar::DiagnosticList diagnostics;
        if (grammar::resolveParameters(trees.grammar, overrides, diagnostics) == parameters)
            return species.name;
    }
    return "species" + std::to_string(ordinal);
}

// Loads the atlas of `geometry` under `shape.name` and `key` from the store, or bakes (and
// stores) it. False when the bake fails: `shape.note` says why.
bool bakeOrLoad(impostor::ImpostorBaker& baker, const impostor::ImpostorStore* store,
                const impostor::BakeGeometry& geometry, uint64_t key, const impostor::ViewLayout& layout,
                impostor::ImpostorAtlas& atlas, BakedShapeReport& shape) {
    const impostor::StoreLookup found =
        store ? store->load(shape.name, key, layout, atlas, shape.note) : impostor::StoreLookup::Missing;
    if (found == impostor::StoreLookup::Loaded) {
        shape.outcome = BakeOutcome::Loaded;
        shape.fileBytes = std::filesystem::file_size(store->pathFor(shape.name, key));
    } else {
        std::string bakeError;
        if (!baker.bake(geometry, layout, atlas, bakeError)) {
            shape.note = "not baked: " + bakeError;
            return false;
        }
        atlas.shape = shape.name;
        atlas.contentKey = key;
        shape.outcome = found == impostor::StoreLookup::Corrupt ? BakeOutcome::Rebaked : BakeOutcome::Baked;
        if (store && !store->save(atlas, shape.fileBytes, bakeError)) shape.note = "not stored: " + bakeError;
    }
    shape.gpuBytes = atlas.byteSize();
    return true;
}

} // namespace

std::string SceneImpostorReport::summary() const {
    size_t made = 0, loaded = 0;
    for (const BakedShapeReport& shape : shapes) {
        made += shape.shape >= 0;
        loaded += shape.shape >= 0 && shape.outcome == BakeOutcome::Loaded;
    }
    std::ostringstream text;
    text << "impostors: " << made << " of " << declaredShapes
         << " declared shapes baked (used by this scene): " << made - loaded << " new, " << loaded
         << " loaded from the store";
    if (treeSpecies > 0) text << "; " << treeSpecies << " tree species";
    return text.str();
}

impostor::BakeGeometry treeGeometry(const grammar::CompiledGrammar& grammar,
                                    const std::vector<float>& parameters, uint64_t seed,
                                    const render::TerminalMeshLibrary& meshes, uint32_t grammarIndex,
                                    float sampleSpacing) {
    grammar::ExpansionSettings settings;
    settings.seed = seed;
    grammar::BuildingExpander expander(grammar, settings);
    grammar::BuildingInput tree;
    // The scene builder's tree footprint: a 0.4 m square about the trunk.
    tree.footprint = {{-0.2, -0.2}, {0.2, -0.2}, {0.2, 0.2}, {-0.2, 0.2}};
    tree.parameters = parameters;
    grammar::BuildingOutput output;
    expander.expand(tree, output);
    // Each part shape's coarser mesh and how far it strays in unit scope space (infinite: it
    // drops a colour or a shading, never good enough).
    struct Coarse {
        std::optional<render::TerminalMesh> mesh;
        glm::vec3 deviation{0.0f};
    };
    std::map<const render::TerminalMesh*, Coarse> coarseOf;
    impostor::BakeGeometry geometry;
    geometry.hash = hashBytes(0xcbf29ce484222325ull, output.terminals.data(),
                              output.terminals.size() * sizeof(grammar::TerminalRecord));
    for (const grammar::TerminalRecord& record : output.terminals) {
        const grammar::Terminal t = grammar::unpackTerminal(record);
        const render::TerminalMesh* mesh = meshes.find(grammarIndex, t.shape);
        if (!mesh) continue;
        const glm::vec3 scope(t.size, t.depthRatio * std::min(t.size.x, t.size.y));
        if (sampleSpacing > 0.0f) {
            auto [it, inserted] = coarseOf.try_emplace(mesh);
            if (inserted) {
                it->second.mesh = render::buildCoarserProceduralMesh(grammar.shapes.at(t.shape), *mesh);
                if (it->second.mesh) it->second.deviation = render::meshDeviation(*mesh, *it->second.mesh);
            }
            const Coarse& coarse = it->second;
            if (coarse.mesh && glm::length(coarse.deviation * scope) <= sampleSpacing) mesh = &*coarse.mesh;
        }
        geometry.hash = hashBytes(geometry.hash, &mesh->contentHash, sizeof mesh->contentHash);
        const glm::mat3 rotation = glm::mat3_cast(t.orientation);
        const uint32_t base = uint32_t(geometry.vertices.size());
        for (render::MeshVertex v : mesh->vertices) {
            v.position = t.position + rotation * (v.position * scope);
            v.normal = rotation * render::scopeNormal(v.normal, mesh->nominalSize, scope);
            geometry.vertices.push_back(v);
        }
        for (uint32_t index : mesh->indices) geometry.indices.push_back(base + index);
    }
    return geometry;
}

bool bakeSceneImpostors(const scene::BuiltScene& scene, const render::TerminalMeshLibrary& meshes,
                        const SceneImpostorOptions& options, SceneImpostors& out, SceneImpostorReport& report,
                        std::string& error) {
    const auto start = std::chrono::steady_clock::now();
    out = {};
    report = {};
    if (!options.facadeLayout.validate(error) || !options.treeLayout.validate(error)) return false;
    if (options.facadeLayout.sphere != impostor::ViewSphere::Hemisphere ||
        options.treeLayout.sphere != impostor::ViewSphere::FullSphere) {
        error = "facade impostors need a hemisphere layout and tree impostors a full-sphere one";
        return false;
    }
    impostor::ImpostorBaker baker;
    if (!baker.init(error)) return false;
    std::optional<impostor::ImpostorStore> store;
    if (!options.storeDirectory.empty()) store.emplace(options.storeDirectory);

    std::vector<BakeItem> items;
    const size_t buildingGrammars = scene.buildingGrammars.size();
    auto grammarAt = [&](uint32_t g) -> const scene::GrammarBuildings& {
        return g < buildingGrammars ? scene.buildingGrammars[g] : scene.treeGrammars[g - buildingGrammars];
    };
    const uint32_t grammarCount = uint32_t(buildingGrammars + scene.treeGrammars.size());
    out.facadeLayer.resize(grammarCount);
    for (uint32_t g = 0; g < grammarCount; ++g) {
        const scene::GrammarBuildings& entry = grammarAt(g);
        out.facadeLayer[g].assign(entry.grammar.shapes.size(), -1);
        report.declaredShapes += uint32_t(entry.grammar.shapes.size());
        if (g >= buildingGrammars || entry.buildings.empty()) {
            // Tree shapes are drawn as geometry near the camera and as species impostors far away.
            report.skippedUnused += g >= buildingGrammars ? 0 : uint32_t(entry.grammar.shapes.size());
            continue;
        }
        const std::vector<bool> emitted = grammar::emittedShapes(entry.grammar);
        for (size_t s = 0; s < emitted.size(); ++s) {
            if (emitted[s])
                items.push_back({entry.grammar.shapes[s].name, g, int(s), nullptr});
            else
                ++report.skippedUnused;
        }
    }
    for (uint32_t g = uint32_t(buildingGrammars); g < grammarCount; ++g) {
        const scene::GrammarBuildings& trees = grammarAt(g);
        report.skippedUnused += uint32_t(trees.grammar.shapes.size());
        std::map<std::vector<float>, size_t> seen;
        for (const grammar::BuildingInput& tree : trees.buildings) {
            if (!seen.emplace(tree.parameters, seen.size()).second) continue;
            out.speciesParameters.push_back(tree.parameters);
            out.speciesGrammar.push_back(g);
        }
    }
    for (size_t s = 0; s < out.speciesParameters.size(); ++s) {
        const uint32_t g = out.speciesGrammar[s];
        items.push_back({"tree:" + speciesName(scene, grammarAt(g), out.speciesParameters[s], s), g, -1,
                         &out.speciesParameters[s]});
    }

    std::map<uint64_t, int> layerOfKey; // same geometry and layout: one atlas
    const impostor::ImpostorStore* const storeOrNull = store ? &*store : nullptr;
    for (size_t i = 0; i < items.size(); ++i) {
        const BakeItem& item = items[i];
        const auto shapeStart = std::chrono::steady_clock::now();
        const bool tree = item.shape < 0;
        BakedShapeReport shape;
        impostor::ImpostorAtlas atlas;
        uint64_t key = 0;
        bool made = false;
        if (tree) {
            const TreeSpeciesBake species{&grammarAt(item.grammar).grammar, item.grammar, *item.parameters,
                                          scene.config.seed, item.name};
            made = bakeTreeSpecies(baker, storeOrNull, species, meshes, options.treeLayout, atlas, shape);
        } else {
            const render::TerminalMesh& mesh = meshes.mesh(item.grammar, uint16_t(item.shape));
            const impostor::BakeGeometry geometry = impostor::geometryFromMesh(mesh);
            key = impostor::bakeKey(geometry.hash, mesh.nominalSize, options.facadeLayout);
            shape.name = item.name;
            shape.grammar = item.grammar;
            shape.shape = item.shape;
            if (layerOfKey.count(key)) {
                out.facadeLayer[item.grammar][size_t(item.shape)] = layerOfKey[key];
                if (options.progress) options.progress(i + 1, items.size(), item.name);
                continue;
            }
            made = bakeOrLoad(baker, storeOrNull, geometry, key, options.facadeLayout, atlas, shape);
        }
        shape.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - shapeStart).count();
        if (!made) {
            report.shapes.push_back(shape);
            if (options.progress) options.progress(i + 1, items.size(), item.name);
            continue;
        }
        report.fileBytes += shape.fileBytes;
        report.gpuBytes += shape.gpuBytes;
        if (tree) {
            out.species.push_back(std::move(atlas));
            ++report.treeSpecies;
        } else {
            layerOfKey[key] = int(out.facades.size());
            out.facadeLayer[item.grammar][size_t(item.shape)] = int(out.facades.size());
            out.facades.push_back(std::move(atlas));
        }
        report.shapes.push_back(std::move(shape));
        if (options.progress) options.progress(i + 1, items.size(), item.name);
    }
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return true;
}

bool bakeTreeSpecies(impostor::ImpostorBaker& baker, const impostor::ImpostorStore* store,
                     const TreeSpeciesBake& species, const render::TerminalMeshLibrary& meshes,
                     const impostor::ViewLayout& layout, impostor::ImpostorAtlas& atlas,
                     BakedShapeReport& report) {
    const auto start = std::chrono::steady_clock::now();
    report = {};
    report.name = species.name;
    report.grammar = species.grammarIndex;
    // The spacing of the bake's samples, from the full tree's sphere (the views frame it).
    impostor::ImpostorAtlas frame;
    impostor::measureGeometry(
        treeGeometry(*species.grammar, species.parameters, species.seed, meshes, species.grammarIndex),
        frame);
    const float sampleSpacing =
        2.0f * frame.radius / float(layout.innerResolution() * impostor::ImpostorBaker::kSupersampling);
    const impostor::BakeGeometry geometry = treeGeometry(*species.grammar, species.parameters, species.seed,
                                                         meshes, species.grammarIndex, sampleSpacing);
    const uint64_t key = impostor::bakeKey(geometry.hash, glm::vec3(1.0f), layout);
    const bool made = bakeOrLoad(baker, store, geometry, key, layout, atlas, report);
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return made;
}

} // namespace hexlod::lod
