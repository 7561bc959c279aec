#include "hexlod/cells/batch_catalog.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

namespace hexlod::cells {
namespace {

template <class... Ts> struct Overloaded : Ts... { using Ts::operator()...; };
// Clang 14 does not deduce aggregate template arguments by itself (P1816).
template <class... Ts> Overloaded(Ts...) -> Overloaded<Ts...>;

std::string cellName(HexCoord c) {
    return "(" + std::to_string(c.q) + ", " + std::to_string(c.r) + ")";
}

} // namespace

BatchCatalog::BatchCatalog(scene::BuiltScene scene)
    : scene_(std::move(scene)), index_(CellIndex::build(scene_, scene_.config.cellSize)) {
    batchOfMember_.resize(index_.grammarCount());
    for (uint32_t g = 0; g < index_.grammarCount(); ++g)
        batchOfMember_[g].resize(grammar(g).buildings.size());
    const auto batches = index_.batches();
    keys_.reserve(batches.size());
    for (uint32_t b = 0; b < batches.size(); ++b) {
        for (const uint32_t member : batches[b].buildings) batchOfMember_[batches[b].grammar][member] = b;
        keys_.push_back(computeKey(b));
    }
}

uint32_t BatchCatalog::firstBatchOf(HexCoord cell) const {
    const auto of = index_.batchesOf(cell);
    if (of.empty()) throw std::out_of_range("cell " + cellName(cell) + " holds no batch");
    return static_cast<uint32_t>(of.data() - index_.batches().data());
}

const scene::GrammarBuildings& BatchCatalog::grammar(uint32_t g) const {
    const uint32_t buildingGrammars = index_.buildingGrammarCount();
    if (g < buildingGrammars) return scene_.buildingGrammars[g];
    if (g - buildingGrammars < scene_.treeGrammars.size()) return scene_.treeGrammars[g - buildingGrammars];
    throw std::out_of_range("grammar index " + std::to_string(g) + " is not in the scene");
}

grammar::BuildingInput& BatchCatalog::buildingAt(BuildingRef ref) {
    const uint32_t buildingGrammars = index_.buildingGrammarCount();
    auto& list = ref.grammar < buildingGrammars
                     ? scene_.buildingGrammars.at(ref.grammar).buildings
                     : scene_.treeGrammars.at(ref.grammar - buildingGrammars).buildings;
    return list.at(ref.building);
}

glm::dvec3 BatchCatalog::cellOrigin(HexCoord cell) const {
    return glm::dvec3(index_.grid().center(cell), 0.0);
}

std::vector<grammar::BuildingInput> BatchCatalog::inputsOf(uint32_t b) const {
    const Batch& of = batch(b);
    const auto& list = grammar(of.grammar).buildings;
    std::vector<grammar::BuildingInput> inputs;
    inputs.reserve(of.buildings.size());
    for (const uint32_t member : of.buildings) inputs.push_back(list[member]);
    return inputs;
}

cache::BatchKey BatchCatalog::computeKey(uint32_t b) const {
    const Batch& of = batch(b);
    const auto inputs = inputsOf(b);
    cache::BatchKey key;
    key.cell = {of.cell.q, of.cell.r};
    key.grammar = of.grammar;
    key.grammarHash = grammar(of.grammar).grammar.contentHash;
    key.parametersHash = cache::hashBatchParameters(inputs, scene_.config.seed);
    return key;
}

grammar::TerminalSet BatchCatalog::generate(uint32_t b) const {
    return generate(b, inputsOf(b), key(b));
}

grammar::TerminalSet BatchCatalog::generate(uint32_t b, std::span<const grammar::BuildingInput> inputs,
                                            const cache::BatchKey& batchKey) const {
    return expandSnapshot(b, inputs, batchKey).terminals;
}

grammar::BatchResult BatchCatalog::expand(uint32_t b) const {
    const std::vector<grammar::BuildingInput> inputs = inputsOf(b);
    return expandSnapshot(b, inputs, key(b));
}

grammar::BatchResult BatchCatalog::expand(uint32_t b, std::span<const grammar::BuildingInput> inputs,
                                          const cache::BatchKey& batchKey) const {
    return expandSnapshot(b, inputs, batchKey);
}

grammar::ExtrudedSet BatchCatalog::expandExtruded(uint32_t b) const {
    const std::vector<grammar::BuildingInput> inputs = inputsOf(b);
    return expandSnapshot(b, inputs, key(b), true).extruded;
}

grammar::BatchResult BatchCatalog::expandSnapshot(uint32_t b, std::span<const grammar::BuildingInput> inputs,
                                                  const cache::BatchKey& batchKey, bool extrudedOnly) const {
    const Batch& of = batch(b);
    grammar::BatchInput input;
    input.grammar = &grammar(of.grammar).grammar;
    input.buildings = inputs;
    input.settings.seed = scene_.config.seed;
    input.settings.cellOrigin = cellOrigin(of.cell);
    input.settings.extrudedOnly = extrudedOnly;
    input.cell = {of.cell.q, of.cell.r};
    input.grammarIndex = of.grammar;
    grammar::BatchResult result = grammar::expandBatch(input);
    result.terminals.header.key = batchKey.digest();
    return result;
}

std::shared_ptr<const grammar::TerminalSet> BatchCatalog::fetch(uint32_t b,
                                                                cache::TerminalSetCache& cache) const {
    const cache::BatchKey& batchKey = key(b);
    return cache.getOrGenerate(batchKey, [&] { return generate(b); });
}

bool BatchCatalog::select(const Selector& selector, std::vector<BuildingRef>& out, std::string& error) const {
    const auto wholeGrammar = [&](uint32_t g) {
        for (uint32_t i = 0; i < grammar(g).buildings.size(); ++i) out.push_back({g, i});
    };
    const auto visitor = Overloaded{
        [&](const std::vector<BuildingRef>& refs) {
            for (const BuildingRef& ref : refs) {
                if (ref.grammar >= index_.grammarCount() ||
                    ref.building >= grammar(ref.grammar).buildings.size()) {
                    error = "building " + std::to_string(ref.building) + " of grammar " +
                            std::to_string(ref.grammar) + " is not in the scene";
                    return;
                }
                out.push_back(ref);
            }
        },
        [&](const BuildingIds& ids) {
            // One pass over the building grammars instead of one per id.
            std::unordered_map<uint32_t, std::optional<BuildingRef>> wanted;
            for (const uint32_t id : ids.ids) wanted.emplace(id, std::nullopt);
            for (uint32_t g = 0; g < index_.buildingGrammarCount(); ++g) {
                const auto& list = grammar(g).buildings;
                for (uint32_t i = 0; i < list.size(); ++i) {
                    const auto it = wanted.find(list[i].id);
                    if (it != wanted.end()) it->second = BuildingRef{g, i};
                }
            }
            for (const uint32_t id : ids.ids) {
                const std::optional<BuildingRef>& ref = wanted.at(id);
                if (!ref) {
                    error = "building id " + std::to_string(id) + " is not in the scene";
                    return;
                }
                out.push_back(*ref);
            }
        },
        [&](HexCoord cell) {
            for (const Batch& of : index_.batchesOf(cell))
                for (const uint32_t member : of.buildings) out.push_back({of.grammar, member});
            if (out.empty()) error = "cell " + cellName(cell) + " holds no building";
        },
        [&](GrammarIndex g) {
            if (g.index >= index_.grammarCount()) {
                error = "grammar index " + std::to_string(g.index) + " is not in the scene";
                return;
            }
            wholeGrammar(g.index);
        },
        [&](const GrammarName& name) {
            for (uint32_t g = 0; g < index_.grammarCount(); ++g)
                if (grammar(g).name == name.name) return wholeGrammar(g);
            error = "grammar '" + name.name + "' is not in the scene";
        },
    };
    std::visit(visitor, selector);
    if (!error.empty()) return false;
    if (out.empty()) {
        error = "the selection holds no building";
        return false;
    }
    // A building listed twice is edited once and saved once, so undo restores its first state.
    std::sort(out.begin(), out.end(), [](BuildingRef a, BuildingRef b) {
        return std::tie(a.grammar, a.building) < std::tie(b.grammar, b.building);
    });
    out.erase(std::unique(out.begin(), out.end(),
                          [](BuildingRef a, BuildingRef b) {
                              return a.grammar == b.grammar && a.building == b.building;
                          }),
              out.end());
    return true;
}

EditResult BatchCatalog::setParams(const Selector& selector, const scene::ParameterMap& values) {
    EditResult result;
    if (values.empty()) {
        result.error = "no parameter values given";
        return result;
    }
    std::vector<BuildingRef> selected;
    if (!select(selector, selected, result.error)) return result;

    std::set<uint32_t> grammars;
    for (const BuildingRef& ref : selected) grammars.insert(ref.grammar);
    for (const auto& [name, value] : values) {
        bool declared = false;
        for (const uint32_t g : grammars) {
            const grammar::CompiledGrammar& compiled = grammar(g).grammar;
            const int p = compiled.findParameter(name);
            if (p < 0) continue;
            declared = true;
            const grammar::ParameterInfo& info = compiled.params[p];
            if (!std::isfinite(value) || value < info.minValue || value > info.maxValue) {
                result.error = "parameter '" + name + "' = " + std::to_string(value) + " is outside [" +
                               std::to_string(info.minValue) + ", " + std::to_string(info.maxValue) +
                               "] of grammar '" + grammar(g).name + "'";
                return result;
            }
        }
        if (!declared) {
            result.error = "parameter '" + name + "' is not declared by any selected grammar";
            return result;
        }
    }

    Edit edit;
    edit.before.reserve(selected.size());
    for (const BuildingRef& ref : selected) {
        grammar::BuildingInput& building = buildingAt(ref);
        edit.before.push_back({ref, building.parameters});
        const grammar::CompiledGrammar& compiled = grammar(ref.grammar).grammar;
        // An empty vector means the defaults; materialise them so one value can change.
        if (building.parameters.empty()) building.parameters = compiled.defaultParameters();
        for (const auto& [name, value] : values) {
            const int p = compiled.findParameter(name);
            if (p >= 0) building.parameters[p] = static_cast<float>(value);
        }
    }
    result.changed = rekey(edit.before);
    history_.push_back(std::move(edit));
    result.ok = true;
    return result;
}

EditResult BatchCatalog::undo() {
    EditResult result;
    if (history_.empty()) {
        result.error = "no edit to undo";
        return result;
    }
    Edit edit = std::move(history_.back());
    history_.pop_back();
    for (const SavedParameters& saved : edit.before) buildingAt(saved.building).parameters = saved.parameters;
    result.changed = rekey(edit.before);
    result.ok = true;
    return result;
}

std::vector<KeyChange> BatchCatalog::rekey(std::span<const SavedParameters> buildings) {
    std::set<uint32_t> batches;
    for (const SavedParameters& saved : buildings)
        batches.insert(batchOfMember_[saved.building.grammar][saved.building.building]);
    std::vector<KeyChange> changed;
    for (const uint32_t b : batches) {
        const cache::BatchKey after = computeKey(b);
        if (after == keys_[b]) continue;
        changed.push_back({b, keys_[b], after});
        keys_[b] = after;
    }
    return changed;
}

} // namespace hexlod::cells
