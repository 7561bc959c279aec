#include "hexlod/cache/batch_key.h"

#include "hexlod/grammar/position_hash.h"

#include <algorithm>
#include <bit>
#include <utility>
#include <vector>

namespace hexlod::cache {

using grammar::combineKey;

uint64_t BatchKey::digest() const {
    uint64_t h = combineKey(0x6878626174636831ull, static_cast<uint32_t>(cell.q)); // "hxbatch1"
    h = combineKey(h, static_cast<uint32_t>(cell.r));
    h = combineKey(h, grammar);
    h = combineKey(h, grammarHash);
    return combineKey(h, parametersHash);
}

std::string BatchKey::hex() const {
    return hexDigest(digest());
}

std::string hexDigest(uint64_t digest) {
    static constexpr char kDigits[] = "0123456789abcdef";
    std::string text(16, '0');
    for (int i = 0; i < 16; ++i) text[15 - i] = kDigits[(digest >> (4 * i)) & 0xf];
    return text;
}

uint64_t hashBuildingInput(const grammar::BuildingInput& b) {
    uint64_t h = combineKey(b.id, b.parameters.size());
    for (float value : b.parameters) h = combineKey(h, std::bit_cast<uint32_t>(value));
    h = combineKey(h, b.footprint.size());
    for (const glm::dvec2& p : b.footprint) {
        h = combineKey(h, std::bit_cast<uint64_t>(p.x));
        h = combineKey(h, std::bit_cast<uint64_t>(p.y));
    }
    return combineKey(h, std::bit_cast<uint64_t>(b.baseElevation));
}

uint64_t hashBatchParameters(std::span<const grammar::BuildingInput> buildings, uint64_t sceneSeed) {
    // (id, hash of the building) pairs sorted by both: the order of the input cannot leak
    // into the key, not even when ids repeat.
    std::vector<std::pair<uint32_t, uint64_t>> perBuilding;
    perBuilding.reserve(buildings.size());
    for (const grammar::BuildingInput& b : buildings) perBuilding.emplace_back(b.id, hashBuildingInput(b));
    std::sort(perBuilding.begin(), perBuilding.end());
    uint64_t h = combineKey(sceneSeed, perBuilding.size());
    for (const auto& [id, buildingHash] : perBuilding) h = combineKey(combineKey(h, id), buildingHash);
    return h;
}

} // namespace hexlod::cache
