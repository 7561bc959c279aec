#include "hexlod/scene/geojson_footprints.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hexlod::scene {
namespace {

const char* kTwoBuildings = R"({"type": "FeatureCollection", "features": [
  {"type": "Feature", "properties": {"height": 12.5},
   "geometry": {"type": "Polygon", "coordinates": [[[5.0, 52.0], [5.001, 52.0], [5.001, 52.001], [5.0, 52.0]]]}},
  {"type": "Feature", "properties": {"height": "9"},
   "geometry": {"type": "MultiPolygon", "coordinates": [
     [[[5.002, 52.0], [5.003, 52.0], [5.003, 52.001], [5.002, 52.0]]],
     [[[5.004, 52.0], [5.005, 52.0], [5.005, 52.001], [5.004, 52.0]],
      [[5.0041, 52.0001], [5.0042, 52.0001], [5.0042, 52.0002], [5.0041, 52.0001]]]]}}
]})";

TEST(GeoJson, PolygonsAndMultiPolygonPartsBecomeBuildings) {
    ImportedFootprints out;
    std::string error;
    ASSERT_TRUE(parseGeoJsonFootprints(kTwoBuildings, out, error)) << error;
    EXPECT_EQ(out.features, 2u);
    ASSERT_EQ(out.buildings.size(), 3u);
    EXPECT_EQ(out.buildings[2].id, 2u);
    EXPECT_EQ(out.holesIgnored, 1u);
    EXPECT_TRUE(out.skipped.empty());
    EXPECT_DOUBLE_EQ(out.heights[0], 12.5);
    EXPECT_DOUBLE_EQ(out.heights[1], 9.0);
    EXPECT_DOUBLE_EQ(out.heights[2], 9.0);
    // The projection centre is the middle of the data's bounding box.
    EXPECT_NEAR(out.originLon, 5.0025, 1e-12);
    EXPECT_NEAR(out.originLat, 52.0005, 1e-12);
}

TEST(GeoJson, ProjectionScaleMatchesTheEllipsoid) {
    // At 52 degrees north a degree of latitude is 111,263 m and of longitude 68,677 m
    // (WGS84 meridional and parallel arc lengths).
    const LocalProjection p = LocalProjection::about(5.0, 52.0);
    EXPECT_NEAR(p.metresPerDegreeLat, 111263.0, 5.0);
    EXPECT_NEAR(p.metresPerDegreeLon, 68677.0, 5.0);
    const glm::dvec2 q = p.project(5.001, 52.001);
    EXPECT_NEAR(q.x, 68.677, 0.01);
    EXPECT_NEAR(q.y, 111.263, 0.01);
}

TEST(GeoJson, BadFeaturesAreSkippedAndCountedWithTheirReason) {
    const char* text = R"({"type": "FeatureCollection", "features": [
      {"type": "Feature", "geometry": {"type": "Point", "coordinates": [5, 52]}},
      {"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [[[5, 52], [5.1, 52], [5, 52]]]}},
      {"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [[[5, 52], [500, 52], [5, 53], [5, 52]]]}},
      {"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [[[5, 52], ["a", 52], [5, 53], [5, 52]]]}},
      {"type": "Feature"},
      {"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [[[5, 52], [5.1, 52], [5, 52.1], [5, 52]]]}}
    ]})";
    ImportedFootprints out;
    std::string error;
    ASSERT_TRUE(parseGeoJsonFootprints(text, out, error)) << error;
    EXPECT_EQ(out.features, 6u);
    EXPECT_EQ(out.buildings.size(), 1u);
    EXPECT_EQ(out.skipped["geometry is not a Polygon or MultiPolygon"], 1u);
    EXPECT_EQ(out.skipped["ring has fewer than 4 positions"], 1u);
    EXPECT_EQ(out.skipped["coordinate outside lon/lat range"], 1u);
    EXPECT_EQ(out.skipped["position is not [lon, lat]"], 1u);
    EXPECT_EQ(out.skipped["feature has no geometry"], 1u);
    EXPECT_TRUE(std::isnan(out.heights[0]));
}

TEST(GeoJson, DocumentsThatAreNotGeoJsonFail) {
    ImportedFootprints out;
    std::string error;
    EXPECT_FALSE(parseGeoJsonFootprints("{not json", out, error));
    EXPECT_EQ(error, "not valid JSON");
    EXPECT_FALSE(parseGeoJsonFootprints("[1, 2]", out, error));
    EXPECT_FALSE(parseGeoJsonFootprints(R"({"type": "FeatureCollection"})", out, error));
    EXPECT_NE(error.find("features"), std::string::npos);
    EXPECT_FALSE(readGeoJsonFootprints("/nonexistent.geojson", out, error));
    EXPECT_NE(error.find("cannot open"), std::string::npos);
}

TEST(GeoJson, ShippedUtrechtFootprints) {
    ImportedFootprints out;
    std::string error;
    ASSERT_TRUE(readGeoJsonFootprints(HEXLOD_SHARED_DATA_DIR "/geojson/utrecht_overture_buildings.geojson",
                                      out, error))
        << error;
    EXPECT_EQ(out.features, 3754u);
    EXPECT_TRUE(out.skipped.empty());
    EXPECT_GE(out.buildings.size(), 3754u);
    size_t withHeight = 0;
    for (double h : out.heights) withHeight += std::isfinite(h);
    EXPECT_EQ(withHeight, 15u); // data/README.md: `height` is set on 15 features
    // Local coordinates stay within a few kilometres of the centre.
    for (const grammar::BuildingInput& b : out.buildings) {
        for (const glm::dvec2& p : b.footprint) ASSERT_LT(glm::length(p), 10000.0);
    }
}

} // namespace
} // namespace hexlod::scene
