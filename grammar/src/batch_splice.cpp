#include "hexlod/grammar/batch_splice.h"

#include <algorithm>
#include <cassert>

namespace hexlod::grammar {
namespace {

bool isReplaced(std::span<const uint32_t> replaced, uint32_t building) {
    return std::binary_search(replaced.begin(), replaced.end(), building);
}

// Base records of one shape, minus the replaced buildings', merged with the replacement's by
// building id. Runs between replaced buildings are copied whole.
void mergeShape(const TerminalRecord* base, size_t baseCount, const TerminalRecord* replacement,
                size_t replacementCount, std::span<const uint32_t> replaced, TerminalRecord*& out) {
    size_t i = 0, j = 0;
    while (i < baseCount || j < replacementCount) {
        if (i < baseCount && isReplaced(replaced, base[i].building)) {
            ++i;
            continue;
        }
        if (j < replacementCount && (i == baseCount || replacement[j].building < base[i].building)) {
            *out++ = replacement[j++];
            continue;
        }
        // A run of base records up to the next replacement record or replaced building.
        const uint32_t stop = j < replacementCount ? replacement[j].building : UINT32_MAX;
        const size_t start = i;
        while (i < baseCount && base[i].building <= stop && !isReplaced(replaced, base[i].building)) ++i;
        out = std::copy(base + start, base + i, out);
    }
}

} // namespace

TerminalSet spliceTerminals(const TerminalSet& base, const TerminalSet& replacement,
                            std::span<const uint32_t> replaced) {
    assert(std::is_sorted(replaced.begin(), replaced.end()));
    TerminalSet out;
    out.header = base.header;
    const size_t shapes = std::max(base.countPerShape.size(), replacement.countPerShape.size());
    const auto count = [](const TerminalSet& set, size_t s) {
        return s < set.countPerShape.size() ? size_t(set.countPerShape[s]) : size_t(0);
    };
    size_t removed = 0;
    for (const TerminalRecord& r : base.records) removed += isReplaced(replaced, r.building);
    out.records.resize(base.records.size() - removed + replacement.records.size());
    out.countPerShape.assign(shapes, 0);
    const TerminalRecord* baseShape = base.records.data();
    const TerminalRecord* replacementShape = replacement.records.data();
    TerminalRecord* cursor = out.records.data();
    for (size_t s = 0; s < shapes; ++s) {
        TerminalRecord* const first = cursor;
        mergeShape(baseShape, count(base, s), replacementShape, count(replacement, s), replaced, cursor);
        out.countPerShape[s] = uint32_t(cursor - first);
        baseShape += count(base, s);
        replacementShape += count(replacement, s);
    }
    assert(cursor == out.records.data() + out.records.size());
    return out;
}

ExtrudedSet spliceExtruded(const ExtrudedSet& base, const ExtrudedSet& replacement,
                           std::span<const uint32_t> replaced) {
    ExtrudedSet out;
    const auto append = [&out](const ExtrudedSet& from, size_t index) {
        const ExtrudedBuilding& b = from.buildings[index];
        const size_t parametersEnd = index + 1 < from.buildings.size()
                                         ? from.buildings[index + 1].firstParameter
                                         : from.parameters.size();
        ExtrudedBuilding moved = b;
        moved.firstVertex = uint32_t(out.footprints.size());
        moved.firstElement = uint32_t(out.elements.size());
        moved.firstParameter = uint32_t(out.parameters.size());
        out.buildings.push_back(moved);
        out.footprints.insert(out.footprints.end(), from.footprints.begin() + b.firstVertex,
                              from.footprints.begin() + b.firstVertex + b.vertexCount);
        out.elements.insert(out.elements.end(), from.elements.begin() + b.firstElement,
                            from.elements.begin() + b.firstElement + b.elementCount);
        out.parameters.insert(out.parameters.end(), from.parameters.begin() + b.firstParameter,
                              from.parameters.begin() + parametersEnd);
    };
    out.buildings.reserve(base.buildings.size() + replacement.buildings.size());
    size_t i = 0, j = 0;
    while (i < base.buildings.size() || j < replacement.buildings.size()) {
        if (i < base.buildings.size() && isReplaced(replaced, base.buildings[i].building)) {
            ++i;
        } else if (j < replacement.buildings.size() &&
                   (i == base.buildings.size() ||
                    replacement.buildings[j].building < base.buildings[i].building)) {
            append(replacement, j++);
        } else {
            append(base, i++);
        }
    }
    return out;
}

} // namespace hexlod::grammar
