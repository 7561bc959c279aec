// Building footprints from GeoJSON (RFC 7946): Polygon and MultiPolygon features in WGS84
// lon/lat, projected to local metres about the centre of the data.
#pragma once

#include "hexlod/grammar/expander.h"

#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace hexlod::scene {

struct ImportedFootprints {
    std::vector<grammar::BuildingInput> buildings; // ids 0.. in file order, one per polygon
    std::vector<double> heights;                   // metres from the `height` property; NaN if absent
    double originLon = 0.0, originLat = 0.0;       // projection centre (degrees)
    size_t features = 0;
    size_t holesIgnored = 0;               // inner rings: footprints are outer rings
    std::map<std::string, size_t> skipped; // reason -> features skipped for it
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

// Parses GeoJSON text. A malformed feature is skipped and counted with its reason; only a
// document that is not JSON or not a FeatureCollection/Feature/geometry fails, with `error`.
bool parseGeoJsonFootprints(std::string_view text, ImportedFootprints& out, std::string& error);
bool readGeoJsonFootprints(const std::string& path, ImportedFootprints& out, std::string& error);

} // namespace hexlod::scene
