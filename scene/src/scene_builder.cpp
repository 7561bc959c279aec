#include "hexlod/scene/scene_builder.h"

#include "hexlod/scene/building_floors.h"
#include "hexlod/scene/demo_footprints.h"
#include "hexlod/scene/geojson_footprints.h"
#include "hexlod/scene/osm_footprints.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace hexlod::scene {
namespace {

struct BuildError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

std::vector<grammar::ParameterOverride> toOverrides(const ParameterMap& params) {
    std::vector<grammar::ParameterOverride> list;
    for (const auto& [name, value] : params) list.push_back({name, value});
    return list;
}

// Resolves a building's parameters; a bad name or value is an error naming `field`.
std::vector<float> resolve(const grammar::CompiledGrammar& g,
                           const std::vector<grammar::ParameterOverride>& list, const std::string& field) {
    grammar::DiagnosticList diagnostics;
    std::vector<float> values = grammar::resolveParameters(g, list, diagnostics);
    if (diagnostics.hasErrors()) throw BuildError(field + ": " + diagnostics.all().front().message);
    return values;
}

class Builder {
public:
    Builder(const SceneConfig& config, BuiltScene& out) : config_(config), out_(out) {}

    void run() {
        out_.config = config_;
        for (const GrammarEntry& entry : config_.grammars) {
            GrammarBuildings batch;
            batch.name = entry.name;
            batch.grammar = compile(entry.path, "grammars." + entry.name);
            resolve(batch.grammar, toOverrides(entry.params), "grammars." + entry.name + ".params");
            out_.buildingGrammars.push_back(std::move(batch));
        }
        for (size_t i = 0; i < config_.sources.size(); ++i) addSource(i);
        for (const GrammarBuildings& batch : out_.buildingGrammars) {
            if (batch.buildings.empty())
                out_.notes.push_back("grammar " + batch.name + ": unused (no buildings)");
        }
        if (config_.trees.count == 0) {
            out_.notes.push_back("vegetation: off (no trees)");
        } else if (trees_.empty()) {
            out_.notes.push_back("vegetation: off (no procedural source places trees)");
        } else {
            addTrees();
        }
    }

private:
    grammar::CompiledGrammar compile(const std::string& path, const std::string& field) {
        grammar::DiagnosticList diagnostics;
        grammar::CompiledGrammar g = grammar::compileGrammarFile(path, diagnostics);
        if (diagnostics.hasErrors()) throw BuildError(field + ": " + diagnostics.formatAll());
        return g;
    }

    // Per-building overrides of source `source`, keyed by the source's own building id.
    std::map<uint32_t, const ParameterMap*> overridesOf(size_t source) const {
        std::map<uint32_t, const ParameterMap*> map;
        for (const BuildingOverride& entry : config_.overrides) {
            if (entry.source != source) continue;
            for (uint32_t id : entry.buildings) map[id] = &entry.params;
        }
        return map;
    }

    void addBuilding(size_t source, uint32_t localId, int grammarIndex, grammar::BuildingInput input,
                     double floors, const std::map<uint32_t, const ParameterMap*>& overrides) {
        GrammarBuildings& batch = out_.buildingGrammars[grammarIndex];
        std::vector<grammar::ParameterOverride> list = toOverrides(config_.grammars[grammarIndex].params);
        appendFloors(batch.grammar, floors, list);
        const auto it = overrides.find(localId);
        if (it != overrides.end()) {
            const std::vector<grammar::ParameterOverride> mine = toOverrides(*it->second);
            list.insert(list.end(), mine.begin(), mine.end());
        }
        const std::string field = it != overrides.end() ? "overrides (buildings[" + std::to_string(source) +
                                                              "] building " + std::to_string(localId) + ")"
                                                        : "buildings[" + std::to_string(source) + "]";
        input.parameters = resolve(batch.grammar, list, field);
        input.id = nextId_++;
        out_.buildingOrigins.push_back({static_cast<uint32_t>(source), localId});
        batch.buildings.push_back(std::move(input));
    }

    void addSource(size_t index) {
        const BuildingSource& source = config_.sources[index];
        const std::string field = "buildings[" + std::to_string(index) + "]";
        const auto overrides = overridesOf(index);
        if (source.kind == BuildingSourceKind::Procedural) {
            GeneratedCity city;
            try {
                city = generateCity(source.city);
            } catch (const std::invalid_argument& e) {
                throw BuildError(field + ": " + e.what());
            }
            for (GeneratedBuilding& b : city.buildings) {
                const int g = config_.findGrammar(source.city.districts[b.district].grammar);
                addBuilding(index, b.input.id, g, std::move(b.input), b.floors, overrides);
            }
            trees_.insert(trees_.end(), city.trees.begin(), city.trees.end());
            out_.roads.insert(out_.roads.end(), city.roads.begin(), city.roads.end());
            out_.notes.push_back(field + ": procedural city of " + std::to_string(city.buildings.size()) +
                                 " buildings, " + std::to_string(city.trees.size()) + " trees");
            return;
        }
        ImportedFootprints imported;
        std::string error;
        const bool ok = source.kind == BuildingSourceKind::Osm
                            ? readOsmFootprints(source.path, imported, error)
                            : readGeoJsonFootprints(source.path, imported, error);
        if (!ok) throw BuildError(field + ".path: " + error);
        const int g = config_.findGrammar(source.grammar);
        for (size_t i = 0; i < imported.buildings.size(); ++i) {
            const double levels = i < imported.levels.size() ? imported.levels[i] : NAN;
            const grammar::CompiledGrammar& compiled = out_.buildingGrammars[g].grammar;
            double floors = floorsFromImport(compiled, imported.heights[i], levels);
            if (!std::isfinite(floors)) {
                // No height in the data: the scene's default storeys, varied by seed and building.
                const auto seeded = demoParameterOverrides(compiled, config_.seed, imported.buildings[i].id);
                if (!seeded.empty()) floors = seeded.front().value;
            }
            addBuilding(index, imported.buildings[i].id, g, std::move(imported.buildings[i]), floors,
                        overrides);
        }
        size_t skipped = 0;
        for (const auto& [reason, count] : imported.skipped) skipped += count;
        out_.notes.push_back(field + ": imported " + std::to_string(imported.buildings.size()) +
                             " footprints from " + std::to_string(imported.features) + " features, skipped " +
                             std::to_string(skipped));
        if (!imported.attribution.empty()) out_.attributions.push_back(imported.attribution);
    }

    void addTrees() {
        // One batch per distinct species grammar; each tree is a 0.4 m footprint at its
        // position, so the grammar grows exactly one tree from it.
        std::map<std::string, size_t> batchOf;
        std::vector<std::vector<float>> speciesParams;
        std::vector<size_t> speciesBatch;
        for (size_t s = 0; s < config_.trees.species.size(); ++s) {
            const TreeSpecies& species = config_.trees.species[s];
            auto [it, inserted] = batchOf.emplace(species.grammar, out_.treeGrammars.size());
            if (inserted) {
                GrammarBuildings batch;
                batch.name = species.grammar;
                batch.grammar = compile(species.grammar, "trees.species[" + std::to_string(s) + "].grammar");
                out_.treeGrammars.push_back(std::move(batch));
            }
            speciesBatch.push_back(it->second);
            speciesParams.push_back(resolve(out_.treeGrammars[it->second].grammar,
                                            toOverrides(species.params),
                                            "trees.species[" + std::to_string(s) + "].params"));
        }
        uint32_t id = 0;
        for (const TreeInstance& tree : trees_) {
            const size_t s = tree.species % config_.trees.species.size();
            grammar::BuildingInput input;
            input.id = id++;
            const double half = 0.2 * tree.scale;
            const glm::dvec2 p = tree.position;
            input.footprint = {p + glm::dvec2(-half, -half), p + glm::dvec2(half, -half),
                               p + glm::dvec2(half, half), p + glm::dvec2(-half, half)};
            input.parameters = speciesParams[s];
            out_.treeSpecies.push_back(static_cast<uint32_t>(s));
            out_.treeGrammars[speciesBatch[s]].buildings.push_back(std::move(input));
        }
        out_.notes.push_back("vegetation: " + std::to_string(trees_.size()) + " trees of " +
                             std::to_string(config_.trees.species.size()) + " species");
    }

    const SceneConfig& config_;
    BuiltScene& out_;
    std::vector<TreeInstance> trees_;
    uint32_t nextId_ = 0;
};

} // namespace

size_t BuiltScene::buildingCount() const {
    size_t n = 0;
    for (const GrammarBuildings& batch : buildingGrammars) n += batch.buildings.size();
    return n;
}

size_t BuiltScene::treeCount() const {
    size_t n = 0;
    for (const GrammarBuildings& batch : treeGrammars) n += batch.buildings.size();
    return n;
}

// Moves everything by the config's origin, in double, so a city far from the world origin
// is the same city (the far-from-origin tests and benchmarks place it 1e7 m out).
void placeAtOrigin(BuiltScene& scene) {
    const glm::dvec3 origin(scene.config.origin[0], scene.config.origin[1], scene.config.origin[2]);
    if (origin == glm::dvec3(0.0)) return;
    for (auto* grammars : {&scene.buildingGrammars, &scene.treeGrammars}) {
        for (GrammarBuildings& grammar : *grammars) {
            for (grammar::BuildingInput& b : grammar.buildings) {
                for (glm::dvec2& p : b.footprint) p += glm::dvec2(origin);
                b.baseElevation += origin.z;
            }
        }
    }
    for (RoadSegment& road : scene.roads) {
        road.a += glm::dvec2(origin);
        road.b += glm::dvec2(origin);
    }
    scene.notes.push_back("origin: placed at " + std::to_string(origin.x) + ", " + std::to_string(origin.y) +
                          ", " + std::to_string(origin.z));
}

bool buildScene(const SceneConfig& config, BuiltScene& out, std::string& error) {
    BuiltScene scene;
    try {
        Builder(config, scene).run();
        placeAtOrigin(scene);
    } catch (const BuildError& e) {
        error = config.file + ": " + e.what();
        return false;
    }
    out = std::move(scene);
    return true;
}

} // namespace hexlod::scene
