// libFuzzer target for the extruded-set decoder (docs/protocol.md, "Extruded set, version 1"):
// arbitrary bytes must be rejected with a reason or decode to a set that re-encodes and
// decodes to itself. Together with ASan this checks that no input reads out of bounds or
// allocates what its header merely claims (-rss_limit_mb catches the latter).
#include "fuzz_check.h"

#include "hexlod/grammar/extruded_set_codec.h"

#include <cstdlib>
#include <cstring>

namespace {

using namespace hexlod::grammar;

using hexlod::fuzz::check;

bool sameBits(const void* a, const void* b, size_t bytes) {
    return bytes == 0 || std::memcmp(a, b, bytes) == 0;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    ExtrudedSetHeader header;
    ExtrudedSet set;
    std::string error;
    if (!decodeExtrudedSet({data, size}, header, set, error)) {
        check(!error.empty());
        return 0;
    }
    uint64_t vertices = 0, elements = 0;
    for (const ExtrudedBuilding& b : set.buildings) {
        check(b.firstVertex == vertices && b.firstElement == elements);
        vertices += b.vertexCount;
        elements += b.elementCount;
    }
    check(vertices == set.footprints.size() && elements == set.elements.size());
    const std::vector<uint8_t> again = encodeExtrudedSet(header, set);
    ExtrudedSetHeader header2;
    ExtrudedSet set2;
    check(decodeExtrudedSet(again, header2, set2, error));
    check(set2.buildings.size() == set.buildings.size() && set2.elements.size() == set.elements.size());
    check(sameBits(set.footprints.data(), set2.footprints.data(),
                   set.footprints.size() * sizeof(set.footprints[0])));
    check(sameBits(set.parameters.data(), set2.parameters.data(), set.parameters.size() * sizeof(float)));
    check(header.key == header2.key && header.cell.q == header2.cell.q);
    return 0;
}
