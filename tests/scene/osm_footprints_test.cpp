#include "hexlod/scene/osm_footprints.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

namespace hexlod::scene {
namespace {

std::string writeTemp(const std::string& name, const std::string& text) {
    const std::string path = ::testing::TempDir() + name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

ImportedFootprints importOk(const std::string& path) {
    ImportedFootprints out;
    std::string error;
    EXPECT_TRUE(readOsmFootprints(path, out, error)) << error;
    return out;
}

// A square of `size` degrees (0.0002: about 16 x 22 m) with its south-west corner at
// (lon, lat), as nodes id..id+3.
std::string square(int id, double lon, double lat, double size = 0.0002) {
    std::string s;
    const double corners[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int i = 0; i < 4; ++i) {
        s += "<node id=\"" + std::to_string(id + i) + "\" lon=\"" +
             std::to_string(lon + size * corners[i][0]) + "\" lat=\"" +
             std::to_string(lat + size * corners[i][1]) + "\"/>\n";
    }
    return s;
}

std::string way(int id, const std::vector<int>& nodes, const std::string& tags) {
    std::string s = "<way id=\"" + std::to_string(id) + "\">";
    for (int n : nodes) s += "<nd ref=\"" + std::to_string(n) + "\"/>";
    return s + tags + "</way>\n";
}

std::string osm(const std::string& body) {
    return "<?xml version='1.0' encoding='UTF-8'?>\n<osm version=\"0.6\" generator=\"hexlod test\">\n" +
           body + "</osm>\n";
}

TEST(Osm, ClosedWaysAndMultipolygonRelationsBecomeBuildings) {
    const std::string text =
        osm(square(1, 7.42, 43.73) + square(11, 7.421, 43.73) + square(15, 7.42105, 43.73005, 0.0001) +
            way(100, {1, 2, 3, 4, 1},
                R"(<tag k="building" v="yes"/><tag k="height" v="12 m"/><tag k="building:levels" v="4"/>)") +
            way(101, {1, 2, 3, 4, 1}, R"(<tag k="building" v="no"/>)") +
            way(102, {1, 2, 3, 4}, R"(<tag k="building" v="house"/>)") +
            way(103, {1, 2, 99, 4, 1}, R"(<tag k="building" v="yes"/>)") +
            way(104, {1, 2, 3, 4, 1}, R"(<tag k="landuse" v="grass"/>)") +
            way(110, {11, 12, 13, 14, 11}, "") + way(111, {15, 16, 17, 18, 15}, "") +
            R"(<relation id="200"><member type="way" ref="110" role="outer"/>
               <member type="way" ref="111" role="inner"/>
               <tag k="type" v="multipolygon"/><tag k="building" v="yes"/></relation>)");
    const ImportedFootprints out = importOk(writeTemp("buildings.osm", text));

    EXPECT_EQ(out.features, 4u); // ways 100, 102, 103 and relation 200
    ASSERT_EQ(out.buildings.size(), 2u);
    EXPECT_EQ(out.buildings[1].id, 1u);
    EXPECT_EQ(out.holesIgnored, 1u);
    const std::map<std::string, size_t> skipped = {{"way is not closed", 1},
                                                   {"way references a node missing from the file", 1}};
    EXPECT_EQ(out.skipped, skipped);
    EXPECT_TRUE(out.warnings.empty());
    EXPECT_DOUBLE_EQ(out.heights[0], 12.0);
    EXPECT_DOUBLE_EQ(out.levels[0], 4.0);
    EXPECT_TRUE(std::isnan(out.heights[1]));
    EXPECT_TRUE(std::isnan(out.levels[1]));
    EXPECT_EQ(out.attribution, "© OpenStreetMap contributors");

    // Projected about the centre of the buildings' bounding box, in metres.
    EXPECT_NEAR(out.originLon, 0.5 * (7.42 + 7.4212), 1e-9);
    EXPECT_NEAR(out.originLat, 43.7301, 1e-9);
    const LocalProjection p = LocalProjection::about(out.originLon, out.originLat);
    const std::vector<glm::dvec2>& way100 = out.buildings[0].footprint;
    ASSERT_EQ(way100.size(), 5u); // closed ring, as in GeoJSON
    EXPECT_NEAR(way100[0].x, p.project(7.42, 43.73).x, 1e-6);
    EXPECT_NEAR(way100[0].y, p.project(7.42, 43.73).y, 1e-6);
    EXPECT_NEAR(way100[2].x - way100[0].x, 0.0002 * p.metresPerDegreeLon, 1e-6);
    EXPECT_NEAR(way100[2].y - way100[0].y, 0.0002 * p.metresPerDegreeLat, 1e-6);
    EXPECT_EQ(out.buildings[1].footprint.size(), 5u); // the relation's outer ring
}

TEST(Osm, HeightsAcceptAMetreUnitAndBadTagsOnlyWarn) {
    const char* heights[] = {"12", "12.5", "12m", " 7 m ", "40'", "tall", "-3"};
    const char* levels[] = {"4", "2.5", "0", "x", "", "3", "1"};
    std::string body = square(1, 7.42, 43.73);
    for (int i = 0; i < 7; ++i) {
        body += way(100 + i, {1, 2, 3, 4, 1},
                    std::string(R"(<tag k="building" v="yes"/><tag k="height" v=")") + heights[i] +
                        R"("/><tag k="building:levels" v=")" + levels[i] + R"("/>)");
    }
    const ImportedFootprints out = importOk(writeTemp("heights.osm", osm(body)));
    ASSERT_EQ(out.buildings.size(), 7u);
    EXPECT_DOUBLE_EQ(out.heights[0], 12.0);
    EXPECT_DOUBLE_EQ(out.heights[1], 12.5);
    EXPECT_DOUBLE_EQ(out.heights[2], 12.0);
    EXPECT_DOUBLE_EQ(out.heights[3], 7.0);
    for (int i = 4; i < 7; ++i) EXPECT_TRUE(std::isnan(out.heights[i])) << heights[i];
    EXPECT_DOUBLE_EQ(out.levels[0], 4.0);
    EXPECT_DOUBLE_EQ(out.levels[1], 2.5);
    for (int i = 2; i < 5; ++i) EXPECT_TRUE(std::isnan(out.levels[i])) << levels[i];
    EXPECT_DOUBLE_EQ(out.levels[5], 3.0);
    const std::map<std::string, size_t> warnings = {{"height is not a number of metres", 3},
                                                    {"building:levels is not a positive number", 3}};
    EXPECT_EQ(out.warnings, warnings);
    EXPECT_TRUE(out.skipped.empty());
}

TEST(Osm, BrokenAreasAreSkippedWithTheirReason) {
    const std::string text =
        osm(square(1, 7.42, 43.73) + square(11, 7.421, 43.73) + R"(<node id="20" lon="200.0" lat="43.73"/>)" +
            way(100, {1, 2, 3, 4, 1}, R"(<tag k="building" v="yes"/>)") +
            way(101, {1, 2, 20, 4, 1}, R"(<tag k="building" v="yes"/>)") +
            way(102, {1, 2, 1}, R"(<tag k="building" v="yes"/>)") + way(110, {11, 12, 13}, "") +
            R"(<relation id="200"><member type="way" ref="110" role="outer"/>
               <tag k="type" v="multipolygon"/><tag k="building" v="yes"/></relation>
               <relation id="201"><member type="way" ref="999" role="outer"/>
               <tag k="type" v="multipolygon"/><tag k="building" v="yes"/></relation>)");
    const ImportedFootprints out = importOk(writeTemp("broken.osm", text));
    EXPECT_EQ(out.features, 5u);
    EXPECT_EQ(out.buildings.size(), 1u);
    const std::map<std::string, size_t> skipped = {
        {"coordinate outside lon/lat range", 1},
        {"way has fewer than 4 nodes", 1},
        {"multipolygon not assembled: ring is not closed", 1},
        {"multipolygon relation has members missing from the file", 1}};
    EXPECT_EQ(out.skipped, skipped);
}

TEST(Osm, MissingAndGarbageFilesFailNamingThePath) {
    ImportedFootprints out;
    std::string error;
    const std::string missing = ::testing::TempDir() + "no_such_file.osm.pbf";
    EXPECT_FALSE(readOsmFootprints(missing, out, error));
    EXPECT_NE(error.find(missing), std::string::npos) << error;

    for (const std::string name : {"garbage.osm.pbf", "garbage.osm", "garbage.osm.bz2"}) {
        const std::string path = writeTemp(name, std::string("this is not OSM data\0\x01\x02\xff", 24));
        error.clear();
        EXPECT_FALSE(readOsmFootprints(path, out, error)) << name;
        EXPECT_NE(error.find(path), std::string::npos) << error;
        EXPECT_TRUE(out.buildings.empty());
    }
    const std::string html = writeTemp("page.osm", "<?xml version='1.0'?><html><body/></html>");
    EXPECT_FALSE(readOsmFootprints(html, out, error));
    EXPECT_NE(error.find(html), std::string::npos) << error;
}

TEST(Osm, MonacoLoadsEveryBuildingArea) {
    const ImportedFootprints out = importOk(HEXLOD_SHARED_DATA_DIR "/osm/monaco.osm.pbf");
    // 23,324 closed ways and 3 multipolygon relations of one outer ring each (data/README.md).
    EXPECT_EQ(out.buildings.size(), 23327u);
    EXPECT_EQ(out.holesIgnored, 2u);
    // Building ways that are no area: the file's 23,327 areas are what remains of 23,373.
    EXPECT_EQ(out.features, 23373u);
    const std::map<std::string, size_t> skipped = {{"way area not assembled: self-intersection", 2},
                                                   {"way has fewer than 4 nodes", 34},
                                                   {"way is not closed", 10}};
    EXPECT_EQ(out.skipped, skipped);
    size_t withLevels = 0, withHeight = 0;
    for (size_t i = 0; i < out.buildings.size(); ++i) {
        withLevels += std::isfinite(out.levels[i]);
        withHeight += std::isfinite(out.heights[i]);
        for (const glm::dvec2& q : out.buildings[i].footprint) ASSERT_LT(glm::length(q), 10000.0);
    }
    EXPECT_EQ(withLevels, 1u);
    EXPECT_EQ(withHeight, 0u);
    EXPECT_EQ(out.attribution, "© OpenStreetMap contributors");
}

} // namespace
} // namespace hexlod::scene
