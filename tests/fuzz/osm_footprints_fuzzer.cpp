// libFuzzer target for the OpenStreetMap footprint importer (docs/scene.md, "OpenStreetMap")
// over OSM XML: arbitrary bytes must be refused with "<path>: <reason>", or give footprints
// with at least three finite vertices, ids in order and one height and level count each. The
// importer reads files, so each input goes through a temporary .osm file; PBF shares every
// step after libosmium's decoding.
#include "fuzz_check.h"

#include "hexlod/scene/osm_footprints.h"

using hexlod::fuzz::allFinite;
using hexlod::fuzz::check;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const hexlod::fuzz::InputFile file(data, size, ".osm");
    hexlod::scene::ImportedFootprints out;
    std::string error;
    if (!hexlod::scene::readOsmFootprints(file.path(), out, error)) {
        check(hexlod::fuzz::startsWith(error, file.path() + ": "));
        check(out.buildings.empty());
        return 0;
    }
    check(out.heights.size() == out.buildings.size() && out.levels.size() == out.buildings.size());
    for (size_t i = 0; i < out.buildings.size(); ++i) {
        const hexlod::grammar::BuildingInput& b = out.buildings[i];
        check(b.id == i && b.footprint.size() >= 3);
        for (const glm::dvec2& p : b.footprint) check(allFinite(p.x, p.y));
    }
    return 0;
}
