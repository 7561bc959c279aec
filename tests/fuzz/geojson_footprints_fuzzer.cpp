// libFuzzer target for the GeoJSON footprint importer (docs/scene.md, "GeoJSON"): arbitrary text
// must be refused with a reason, or give footprints that the grammar expander can take: at
// least three finite vertices each, ids in file order, one height and one level count per
// building, and every skipped polygon counted under a reason.
#include "fuzz_check.h"

#include "hexlod/scene/geojson_footprints.h"

using hexlod::fuzz::allFinite;
using hexlod::fuzz::check;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    hexlod::scene::ImportedFootprints out;
    std::string error;
    if (!hexlod::scene::parseGeoJsonFootprints(text, out, error)) {
        check(!error.empty());
        return 0;
    }
    check(out.heights.size() == out.buildings.size() && out.levels.size() == out.buildings.size());
    // Skips are counted per polygon (a MultiPolygon can skip several), so they are not
    // bounded by the feature count; each must have a reason.
    for (const auto& [reason, count] : out.skipped) check(!reason.empty() && count > 0);
    for (size_t i = 0; i < out.buildings.size(); ++i) {
        const hexlod::grammar::BuildingInput& b = out.buildings[i];
        check(b.id == i && b.footprint.size() >= 3);
        for (const glm::dvec2& p : b.footprint) check(allFinite(p.x, p.y));
        check(std::isnan(out.heights[i]) || (allFinite(out.heights[i]) && out.heights[i] > 0.0));
    }
    return 0;
}
