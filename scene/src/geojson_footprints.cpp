#include "hexlod/scene/geojson_footprints.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace hexlod::scene {
namespace {

using Json = nlohmann::json;
using Ring = std::vector<glm::dvec2>; // lon, lat

// Reads one linear ring; returns a reason when it cannot be used.
const char* readRing(const Json& ring, Ring& out) {
    if (!ring.is_array()) return "ring is not an array";
    if (ring.size() < 4) return "ring has fewer than 4 positions";
    out.clear();
    for (const Json& position : ring) {
        if (!position.is_array() || position.size() < 2 || !position[0].is_number() ||
            !position[1].is_number()) {
            return "position is not [lon, lat]";
        }
        const double lon = position[0].get<double>(), lat = position[1].get<double>();
        if (!std::isfinite(lon) || !std::isfinite(lat) || std::fabs(lon) > 180.0 || std::fabs(lat) > 90.0) {
            return "coordinate outside lon/lat range";
        }
        out.push_back({lon, lat});
    }
    return nullptr;
}

double heightOf(const Json& properties) {
    const double unknown = std::numeric_limits<double>::quiet_NaN();
    if (!properties.is_object() || !properties.contains("height")) return unknown;
    const Json& h = properties["height"];
    double value = unknown;
    if (h.is_number()) value = h.get<double>();
    if (h.is_string()) {
        const std::string text = h.get<std::string>();
        char* end = nullptr;
        value = std::strtod(text.c_str(), &end);
        if (end == text.c_str()) value = unknown;
    }
    return std::isfinite(value) && value > 0.0 && value < 2000.0 ? value : unknown;
}

class Reader {
public:
    explicit Reader(ImportedFootprints& out) : out_(out) {}

    void feature(const Json& feature) {
        ++out_.features;
        if (!feature.is_object() || !feature.contains("geometry")) return skip("feature has no geometry");
        const Json properties = feature.value("properties", Json::object());
        geometry(feature["geometry"], heightOf(properties));
    }

    void geometry(const Json& geometry, double height) {
        if (!geometry.is_object() || !geometry.contains("type") || !geometry["type"].is_string() ||
            !geometry.contains("coordinates")) {
            return skip("geometry has no type or coordinates");
        }
        const std::string type = geometry["type"].get<std::string>();
        const Json& coordinates = geometry["coordinates"];
        if (type == "Polygon") return polygon(coordinates, height);
        if (type == "MultiPolygon") {
            if (!coordinates.is_array()) return skip("coordinates are not an array");
            for (const Json& part : coordinates) polygon(part, height);
            return;
        }
        skip("geometry is not a Polygon or MultiPolygon");
    }

    void finish() { appendProjected(pending_, out_); }

private:
    void skip(const std::string& reason) { ++out_.skipped[reason]; }

    void polygon(const Json& rings, double height) {
        if (!rings.is_array() || rings.empty()) return skip("polygon has no rings");
        Ring outer;
        if (const char* reason = readRing(rings[0], outer)) return skip(reason);
        out_.holesIgnored += rings.size() - 1;
        pending_.push_back({std::move(outer), height});
    }

    ImportedFootprints& out_;
    std::vector<LonLatFootprint> pending_;
};

} // namespace

bool parseGeoJsonFootprints(std::string_view text, ImportedFootprints& out, std::string& error) {
    out = ImportedFootprints{};
    const Json document = Json::parse(text.begin(), text.end(), nullptr, false);
    if (document.is_discarded()) {
        error = "not valid JSON";
        return false;
    }
    if (!document.is_object() || !document.contains("type") || !document["type"].is_string()) {
        error = "not a GeoJSON object (no \"type\")";
        return false;
    }
    Reader reader(out);
    const std::string type = document["type"].get<std::string>();
    if (type == "FeatureCollection") {
        if (!document.contains("features") || !document["features"].is_array()) {
            error = "FeatureCollection has no \"features\" array";
            return false;
        }
        for (const Json& feature : document["features"]) reader.feature(feature);
    } else if (type == "Feature") {
        reader.feature(document);
    } else {
        ++out.features;
        reader.geometry(document, std::numeric_limits<double>::quiet_NaN());
    }
    reader.finish();
    return true;
}

bool readGeoJsonFootprints(const std::string& path, ImportedFootprints& out, std::string& error) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        error = "cannot open '" + path + "'";
        return false;
    }
    std::ostringstream text;
    text << in.rdbuf();
    if (!parseGeoJsonFootprints(text.str(), out, error)) {
        error = path + ": " + error;
        return false;
    }
    return true;
}

} // namespace hexlod::scene
