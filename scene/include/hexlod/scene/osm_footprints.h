// Building footprints from OpenStreetMap data (.osm.pbf, .osm XML, .osm.bz2) read with
// libosmium, projected to local metres about the centre of the buildings like the GeoJSON
// importer.
//
// A building is an area whose `building` tag is not "no": a closed way or a multipolygon
// relation. Each outer ring becomes one footprint; inner rings are counted in holesIgnored.
// `features` counts building objects (ways and relations), whether kept or skipped.
// Heights: `height` in metres, lenient about a unit ("12", "12.5", "12 m", "12m"); levels:
// `building:levels`, a positive number. A tag that is present but unusable leaves NaN and is
// counted in `warnings`: the building itself is kept. A broken area (unclosed way, missing
// node, assembly failure, coordinates out of range) is skipped and counted in `skipped`.
#pragma once

#include "hexlod/scene/imported_footprints.h"

#include <string>

namespace hexlod::scene {

// Reads the file the extension names. Only a file that cannot be opened or is not OSM data
// fails, with `error` naming the path; sets out.attribution.
bool readOsmFootprints(const std::string& path, ImportedFootprints& out, std::string& error);

} // namespace hexlod::scene
