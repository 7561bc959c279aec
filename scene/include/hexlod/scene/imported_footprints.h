// Footprints read from real map data (GeoJSON, OpenStreetMap) and the local projection that
// turns their WGS84 lon/lat into metres.
#pragma once

#include "hexlod/grammar/expander.h"

#include <limits>
#include <map>
#include <string>
#include <vector>

namespace hexlod::scene {

struct ImportedFootprints {
    std::vector<grammar::BuildingInput> buildings; // ids 0.. in file order, one per outer ring
    std::vector<double> heights;                   // metres from `height`; NaN if absent or unusable
    std::vector<double> levels;                    // OSM `building:levels`; NaN if absent or unusable
    double originLon = 0.0, originLat = 0.0;       // projection centre (degrees)
    size_t features = 0;                           // GeoJSON features, or OSM building objects
    size_t holesIgnored = 0;                       // inner rings: footprints are outer rings
    std::map<std::string, size_t> skipped;         // reason -> features skipped for it
    // reason -> buildings kept although a tag was unusable (e.g. height "tall": height NaN)
    std::map<std::string, size_t> warnings;
    std::string attribution; // credit the data's licence requires wherever it is shown
};

// Local projection about (lon0, lat0) on the WGS84 ellipsoid: x east and y north in metres,
// x = N cos(lat0) dlon, y = M dlat with the prime-vertical and meridional radii N and M at
// lat0. Within 10 km of the centre the scale error stays below 0.1 %.
struct LocalProjection {
    double lon0 = 0.0, lat0 = 0.0;
    double metresPerDegreeLon = 0.0, metresPerDegreeLat = 0.0;
    static LocalProjection about(double lon0, double lat0);
    glm::dvec2 project(double lon, double lat) const {
        return {(lon - lon0) * metresPerDegreeLon, (lat - lat0) * metresPerDegreeLat};
    }
};

// A footprint as an importer reads it: its outer ring in lon/lat, before projection.
struct LonLatFootprint {
    std::vector<glm::dvec2> outer;
    double height = std::numeric_limits<double>::quiet_NaN();
    double levels = std::numeric_limits<double>::quiet_NaN();
};

// Projects `footprints` about the centre of their bounding box and appends them to `out` as
// buildings with ids in order, with their heights and levels; sets out's origin.
void appendProjected(const std::vector<LonLatFootprint>& footprints, ImportedFootprints& out);

} // namespace hexlod::scene
