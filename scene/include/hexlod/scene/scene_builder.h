// Builds a scene from its config: compiles its grammars, generates or imports its
// buildings and trees, and resolves every building's parameters. What a scene does not use
// (trees, unused grammars) is left out and said so in `notes`.
#pragma once

#include "hexlod/grammar/compiled_grammar.h"
#include "hexlod/scene/scene_config.h"

#include <string>
#include <vector>

namespace hexlod::scene {

struct GrammarBuildings {
    std::string name; // grammar name in the config, or the species grammar's path
    grammar::CompiledGrammar grammar;
    std::vector<grammar::BuildingInput> buildings; // parameters resolved; ids unique in the scene
};

// Where a building came from: the config names buildings by source and the source's own id.
struct BuildingOrigin {
    uint32_t source = 0;   // index into SceneConfig::sources
    uint32_t sourceId = 0; // the id BuildingOverride::buildings uses
};

struct BuiltScene {
    SceneConfig config;
    std::vector<GrammarBuildings> buildingGrammars; // one per config grammar, in config order
    std::vector<GrammarBuildings> treeGrammars;     // one per distinct species grammar; empty without trees
    std::vector<RoadSegment> roads;
    std::vector<std::string> notes;              // what was started, skipped or left out, and why
    std::vector<std::string> attributions;       // e.g. "© OpenStreetMap contributors"
    std::vector<BuildingOrigin> buildingOrigins; // by BuildingInput::id of the building grammars
    std::vector<uint32_t> treeSpecies;           // by tree BuildingInput::id: index into config.trees.species
    size_t buildingCount() const;
    size_t treeCount() const;
};

// Returns false with `error` naming the config field at fault ("default.json:
// grammars.business: ..." or "overrides[0].params: parameter 'floors' = 900 is outside ...").
bool buildScene(const SceneConfig& config, BuiltScene& out, std::string& error);

} // namespace hexlod::scene
