#include "hexlod/cells/cell_index.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace hexlod::cells {
namespace {

using grammar::BuildingInput;
using grammar::CompiledGrammar;

// Estimates a member's height from its resolved parameters (see the header for the rule).
class HeightModel {
public:
    explicit HeightModel(const CompiledGrammar& g) : defaults_(g.defaultParameters()) {
        floors_ = g.findParameter("floors");
        floorHeight_ = g.findParameter("floor_h");
        if (!storeys()) return;
        for (size_t i = 0; i < g.params.size(); ++i) {
            const std::string& name = g.params[i].name;
            if (static_cast<int>(i) != floorHeight_ && name.size() > 2 && name.ends_with("_h")) {
                extras_.push_back(i);
            }
        }
    }

    bool storeys() const { return floors_ >= 0 && floorHeight_ >= 0; }

    double height(const BuildingInput& b) const {
        if (!storeys()) return kDefaultHeight;
        // Empty parameters mean the defaults; a list of another length cannot be trusted.
        const std::vector<float>& p = b.parameters.size() == defaults_.size() ? b.parameters : defaults_;
        double h = double(p[floors_]) * double(p[floorHeight_]);
        for (size_t i : extras_) h += std::max(0.0, double(p[i]));
        return std::max(h, 0.0);
    }

private:
    std::vector<float> defaults_;
    int floors_ = -1, floorHeight_ = -1;
    std::vector<size_t> extras_;
};

struct Member {
    HexCoord cell;
    uint32_t grammar;
    uint32_t building;
    friend bool operator<(const Member& a, const Member& b) {
        if (a.cell != b.cell) return a.cell < b.cell;
        if (a.grammar != b.grammar) return a.grammar < b.grammar;
        return a.building < b.building;
    }
};

const scene::GrammarBuildings& grammarAt(const scene::BuiltScene& s, uint32_t g) {
    return g < s.buildingGrammars.size() ? s.buildingGrammars[g]
                                         : s.treeGrammars[g - s.buildingGrammars.size()];
}

[[noreturn]] void badBuilding(const scene::GrammarBuildings& g, const BuildingInput& b, const char* what) {
    throw std::invalid_argument("cell index: grammar '" + g.name + "' building " + std::to_string(b.id) +
                                ": " + what);
}

} // namespace

glm::dvec2 footprintCentroid(std::span<const glm::dvec2> footprint) {
    if (footprint.empty()) throw std::invalid_argument("footprintCentroid: empty footprint");
    // A closing vertex repeats the first; counting it twice would bias the vertex mean.
    size_t n = footprint.size();
    if (n > 1 && footprint[n - 1] == footprint[0]) --n;
    const glm::dvec2 origin = footprint[0];
    double twiceArea = 0.0, extent = 0.0;
    glm::dvec2 weighted{0.0}, sum{0.0};
    for (size_t i = 0; i < n; ++i) {
        const glm::dvec2 a = footprint[i] - origin;
        const glm::dvec2 b = footprint[(i + 1) % n] - origin;
        const double cross = a.x * b.y - b.x * a.y;
        twiceArea += cross;
        weighted += (a + b) * cross;
        sum += a;
        extent = std::max({extent, std::abs(a.x), std::abs(a.y)});
    }
    // Relative threshold: a sliver whose area vanishes against its extent has no stable centroid.
    if (std::abs(twiceArea) <= 1e-12 * extent * extent || !std::isfinite(twiceArea)) {
        return origin + sum / double(n);
    }
    return origin + weighted / (3.0 * twiceArea);
}

CellIndex CellIndex::build(const scene::BuiltScene& scene, double cellSize) {
    CellIndex index(HexGrid(cellSize, {0.0, 0.0}));
    const HexGrid& grid = index.grid_;
    const uint32_t grammarCount =
        static_cast<uint32_t>(scene.buildingGrammars.size() + scene.treeGrammars.size());
    index.buildingGrammars_ = static_cast<uint32_t>(scene.buildingGrammars.size());
    index.buildings_ = scene.buildingCount();
    index.trees_ = scene.treeCount();

    std::vector<Member> members;
    members.reserve(index.buildings_ + index.trees_);
    for (uint32_t g = 0; g < grammarCount; ++g) {
        const scene::GrammarBuildings& list = grammarAt(scene, g);
        for (uint32_t i = 0; i < list.buildings.size(); ++i) {
            const BuildingInput& b = list.buildings[i];
            if (b.footprint.empty()) badBuilding(list, b, "empty footprint");
            for (const glm::dvec2& p : b.footprint) {
                if (!std::isfinite(p.x) || !std::isfinite(p.y))
                    badBuilding(list, b, "non-finite footprint point");
            }
            if (!std::isfinite(b.baseElevation)) badBuilding(list, b, "non-finite base elevation");
            members.push_back({grid.cellOf(footprintCentroid(b.footprint)), g, i});
        }
    }
    std::sort(members.begin(), members.end());

    std::vector<HeightModel> heights;
    heights.reserve(grammarCount);
    for (uint32_t g = 0; g < grammarCount; ++g) heights.emplace_back(grammarAt(scene, g).grammar);

    index.cellOfMember_.resize(grammarCount);
    for (uint32_t g = 0; g < grammarCount; ++g)
        index.cellOfMember_[g].resize(grammarAt(scene, g).buildings.size());

    const glm::dvec2 hexHalfExtent{grid.inradius(), grid.circumradius()};
    for (size_t m = 0; m < members.size(); ++m) {
        const Member& member = members[m];
        if (index.cells_.empty() || index.cells_.back().cell != member.cell) {
            const glm::dvec2 c = grid.center(member.cell);
            index.cells_.push_back({member.cell, c - hexHalfExtent, c + hexHalfExtent, INFINITY, -INFINITY});
            index.firstBatch_.push_back(static_cast<uint32_t>(index.batches_.size()));
        }
        if (index.batches_.empty() || index.batches_.back().cell != member.cell ||
            index.batches_.back().grammar != member.grammar) {
            size_t count = 1; // members of this batch, so its list is allocated once
            while (m + count < members.size() && members[m + count].cell == member.cell &&
                   members[m + count].grammar == member.grammar) {
                ++count;
            }
            index.batches_.push_back({member.cell, member.grammar, {}});
            index.batches_.back().buildings.reserve(count);
        }
        index.batches_.back().buildings.push_back(member.building);

        const BuildingInput& b = grammarAt(scene, member.grammar).buildings[member.building];
        const HeightModel& model = heights[member.grammar];
        const double height = model.height(b);
        const double margin = model.storeys() ? kFacadeMargin : 0.5 * height;
        CellBounds& bounds = index.cells_.back();
        for (const glm::dvec2& p : b.footprint) {
            bounds.lo = glm::min(bounds.lo, p - margin);
            bounds.hi = glm::max(bounds.hi, p + margin);
        }
        bounds.zMin = std::min(bounds.zMin, b.baseElevation);
        bounds.zMax = std::max(bounds.zMax, b.baseElevation + height);
        index.cellOfMember_[member.grammar][member.building] = static_cast<uint32_t>(index.cells_.size() - 1);
    }
    index.firstBatch_.push_back(static_cast<uint32_t>(index.batches_.size()));
    return index;
}

size_t CellIndex::cellPosition(HexCoord cell) const {
    const auto it = std::lower_bound(cells_.begin(), cells_.end(), cell,
                                     [](const CellBounds& b, HexCoord c) { return b.cell < c; });
    return it != cells_.end() && it->cell == cell ? static_cast<size_t>(it - cells_.begin()) : cells_.size();
}

const CellBounds* CellIndex::boundsOf(HexCoord cell) const {
    const size_t i = cellPosition(cell);
    return i < cells_.size() ? &cells_[i] : nullptr;
}

std::span<const Batch> CellIndex::batchesOf(HexCoord cell) const {
    const size_t i = cellPosition(cell);
    if (i == cells_.size()) return {};
    return std::span<const Batch>(batches_).subspan(firstBatch_[i], firstBatch_[i + 1] - firstBatch_[i]);
}

HexCoord CellIndex::cellOfBuilding(uint32_t grammar, uint32_t building) const {
    if (grammar >= cellOfMember_.size() || building >= cellOfMember_[grammar].size()) {
        throw std::out_of_range("cell index: no building " + std::to_string(building) + " in grammar " +
                                std::to_string(grammar));
    }
    return cells_[cellOfMember_[grammar][building]].cell;
}

size_t CellIndex::memoryBytes() const {
    size_t bytes = sizeof(*this) + cells_.capacity() * sizeof(CellBounds) +
                   firstBatch_.capacity() * sizeof(uint32_t) + batches_.capacity() * sizeof(Batch) +
                   cellOfMember_.capacity() * sizeof(std::vector<uint32_t>);
    for (const Batch& b : batches_) bytes += b.buildings.capacity() * sizeof(uint32_t);
    for (const std::vector<uint32_t>& v : cellOfMember_) bytes += v.capacity() * sizeof(uint32_t);
    return bytes;
}

} // namespace hexlod::cells
