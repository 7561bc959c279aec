#include "hexlod/server/scene_export.h"

#include "hexlod/scene/scene_config_writer.h"
#include "hexlod/server/scene_service.h"

#include <map>
#include <set>

namespace hexlod::server {
namespace {

// The params a building gets from the config's own overrides: the last entry naming it wins
// whole (scene_builder.cpp, overridesOf), so an added entry must repeat them.
const scene::ParameterMap* configOverride(const scene::SceneConfig& config,
                                          const scene::BuildingOrigin& origin) {
    const scene::ParameterMap* found = nullptr;
    for (const scene::BuildingOverride& o : config.overrides)
        if (o.source == origin.source)
            for (const uint32_t id : o.buildings)
                if (id == origin.sourceId) found = &o.params;
    return found;
}

// `base` plus every parameter whose value in `now` differs from `before`.
scene::ParameterMap changedOver(const scene::ParameterMap& base, const grammar::CompiledGrammar& grammar,
                                const std::vector<float>& before, const std::vector<float>& now) {
    scene::ParameterMap params = base;
    for (size_t p = 0; p < grammar.params.size() && p < now.size() && p < before.size(); ++p)
        if (now[p] != before[p]) params[grammar.params[p].name] = static_cast<double>(now[p]);
    return params;
}

} // namespace

bool editedSceneConfig(const scene::SceneConfig& original, const scene::BuiltScene& baseline,
                       const cells::BatchCatalog& edited, scene::SceneConfig& out, ExportReport& report,
                       std::string& error) {
    out = original;
    const scene::BuiltScene& now = edited.scene();
    // Buildings: one override entry per (source, parameter values), in first-seen order.
    std::map<std::pair<uint32_t, scene::ParameterMap>, size_t> entryOf;
    for (size_t g = 0; g < baseline.buildingGrammars.size(); ++g) {
        const scene::GrammarBuildings& before = baseline.buildingGrammars[g];
        const scene::GrammarBuildings& after = now.buildingGrammars.at(g);
        for (size_t i = 0; i < before.buildings.size(); ++i) {
            const grammar::BuildingInput& b = before.buildings[i];
            const std::vector<float>& values = after.buildings.at(i).parameters;
            if (values == b.parameters) continue;
            ++report.editedBuildings;
            const scene::BuildingOrigin origin = baseline.buildingOrigins.at(b.id);
            const scene::ParameterMap* own = configOverride(original, origin);
            scene::ParameterMap params =
                changedOver(own ? *own : scene::ParameterMap{}, before.grammar, b.parameters, values);
            const auto key = std::make_pair(origin.source, params);
            const auto [it, added] = entryOf.try_emplace(key, out.overrides.size());
            if (added) out.overrides.push_back({origin.source, {}, std::move(params)});
            out.overrides[it->second].buildings.push_back(origin.sourceId);
        }
    }
    report.overrides = entryOf.size();

    // Trees: a species' parameters are shared by all its trees, so its trees must agree.
    std::map<uint32_t, const std::vector<float>*> speciesValues;
    std::map<uint32_t, const scene::GrammarBuildings*> speciesGrammar;
    std::set<uint32_t> editedSpecies;
    for (size_t t = 0; t < baseline.treeGrammars.size(); ++t) {
        const scene::GrammarBuildings& before = baseline.treeGrammars[t];
        const scene::GrammarBuildings& after = now.treeGrammars.at(t);
        for (size_t i = 0; i < before.buildings.size(); ++i) {
            const uint32_t species = baseline.treeSpecies.at(before.buildings[i].id);
            const std::vector<float>& values = after.buildings.at(i).parameters;
            const auto [it, first] = speciesValues.try_emplace(species, &values);
            speciesGrammar[species] = &before;
            if (!first && *it->second != values) {
                error = "trees of species '" + original.trees.species.at(species).name +
                        "' carry different edits (edited by cell or one by one); a scene config sets tree "
                        "parameters per species, so this journal cannot be exported";
                return false;
            }
            if (values != before.buildings[i].parameters) editedSpecies.insert(species);
        }
    }
    for (const uint32_t species : editedSpecies) {
        const scene::GrammarBuildings& grammarBuildings = *speciesGrammar.at(species);
        // Every tree of the species started from the same values: take the first one's.
        const std::vector<float>* before = nullptr;
        for (const grammar::BuildingInput& tree : grammarBuildings.buildings)
            if (baseline.treeSpecies.at(tree.id) == species) {
                before = &tree.parameters;
                break;
            }
        scene::TreeSpecies& entry = out.trees.species.at(species);
        entry.params =
            changedOver(entry.params, grammarBuildings.grammar, *before, *speciesValues.at(species));
    }
    report.editedSpecies = editedSpecies.size();
    return true;
}

bool exportEditedScene(const scene::SceneConfig& config, const std::string& journalPath,
                       const std::string& outPath, ExportReport& report, std::string& error) {
    scene::BuiltScene baseline;
    if (!scene::buildScene(config, baseline, error)) return false;
    scene::BuiltScene toEdit = baseline;
    ServiceOptions options;
    options.journalPath = journalPath;
    options.journalReadOnly = true;
    options.generationWorkers = 1;
    std::vector<std::string> log;
    cache::CacheOptions cacheOptions;
    cacheOptions.memoryBudgetBytes = 0;
    const std::unique_ptr<SceneService> service =
        SceneService::create(std::move(toEdit), cacheOptions, options, log, error);
    if (!service) return false;
    for (const std::string& line : log)
        if (line.rfind("journal", 0) == 0) report.notes.push_back(line);
    report.entries = service->history(0, ~size_t(0))["total"].get<size_t>();
    scene::SceneConfig edited;
    const bool ok = service->withCatalog([&](const cells::BatchCatalog& catalog) {
        return editedSceneConfig(config, baseline, catalog, edited, report, error);
    });
    if (!ok) return false;
    return scene::writeSceneConfig(edited, outPath, error);
}

} // namespace hexlod::server
