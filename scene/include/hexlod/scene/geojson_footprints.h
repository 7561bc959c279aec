// Building footprints from GeoJSON (RFC 7946): Polygon and MultiPolygon features in WGS84
// lon/lat, projected to local metres about the centre of the data.
#pragma once

#include "hexlod/scene/imported_footprints.h"

#include <string>
#include <string_view>

namespace hexlod::scene {

// Parses GeoJSON text. A malformed feature is skipped and counted with its reason; only a
// document that is not JSON or not a FeatureCollection/Feature/geometry fails, with `error`.
bool parseGeoJsonFootprints(std::string_view text, ImportedFootprints& out, std::string& error);
bool readGeoJsonFootprints(const std::string& path, ImportedFootprints& out, std::string& error);

} // namespace hexlod::scene
