// Extreme cases, part 2: tall towers and the caps, and degenerate footprints.
#include "pipeline.h"

#include "hexlod/scene/geojson_footprints.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace hexlod::extreme {
namespace {

constexpr const char* kTower = R"(
param floors = 10 in [1, 1000];
shape window(width = 1.2, height = 1.5, depth = 0.25, depth_ratio = 0.12, triangles = 220);
Lot -> Extrude(floors * 3) { Facade, NULL };
Facade -> Repeat(y, 3, equal) { Storey };
Storey -> Repeat(x, 4, fit) { Window };
Window -> Shape(window);
)";

TEST(ExtremeTowers, AThousandFloorTowerHasExactlyItsWindows) {
    // 20 m x 12 m: 5 and 3 bays of 4 m per storey and facade, 16 windows a storey.
    std::vector<grammar::BuildingInput> tower{building(0, rectangle(20.0, 12.0), {1000.0f})};
    const PipelineResult r =
        runPipeline(sceneOf(kTower, std::move(tower)), {lookAt({10, -400, 300}, {10, 6, 1500}), true});
    EXPECT_EQ(r.terminals, 16000u);
    EXPECT_TRUE(r.issues.empty()) << r.issues.front();
    EXPECT_TRUE(r.payloadsRoundTrip);
    EXPECT_TRUE(r.glClean && r.frameFinite);
    EXPECT_GT(r.cull.terminalsPerLod[2] + r.cull.terminalsPerLod[3] + r.cull.terminalsPerLod[4], 0u);
}

TEST(ExtremeTowers, TheTerminalCapIsADiagnosticNamingTheRule) {
    // 1 cm tiles on a 3 km tall facade: far more terminals than an atom may hold.
    constexpr const char* grid = R"(
shape tile(triangles = 2);
Lot -> Extrude(3000) { Facade, NULL };
Facade -> Repeat(y, 0.01, fit) { Row };
Row -> Repeat(x, 0.01, fit) { Tile };
Tile -> Shape(tile);
)";
    std::vector<grammar::BuildingInput> one{building(0, rectangle(50.0, 50.0))};
    const PipelineResult r =
        runPipeline(sceneOf(grid, std::move(one)), {lookAt({25, -100, 50}, {25, 0, 50}), false});
    ASSERT_FALSE(r.issues.empty());
    bool named = false;
    for (const std::string& issue : r.issues) named |= issue.find("extreme.grammar:") != std::string::npos;
    EXPECT_TRUE(named) << r.issues.front();
    EXPECT_TRUE(r.payloadsRoundTrip);
}

TEST(ExtremeTowers, DeepBranchRecursionHitsTheDepthCap) {
    constexpr const char* deep = R"(
shape leaf(triangles = 2);
Lot -> Extrude(3) { Grow, NULL };
Grow -> Cond(depth < 100000) { Again, Leaf };
Again -> Branch(1) { Grow };
Leaf -> Shape(leaf);
)";
    std::vector<grammar::BuildingInput> one{building(0, rectangle(10.0, 10.0))};
    const PipelineResult r =
        runPipeline(sceneOf(deep, std::move(one)), {lookAt({5, -30, 5}, {5, 0, 2}), false});
    ASSERT_FALSE(r.issues.empty());
    EXPECT_NE(r.issues.front().find("depth"), std::string::npos) << r.issues.front();
    EXPECT_FALSE(r.failedBatch);
}

struct FootprintCase {
    const char* name;
    std::vector<glm::dvec2> footprint;
    bool expands; // else skipped with a reason
};

std::vector<glm::dvec2> circle(size_t n, double radius) {
    std::vector<glm::dvec2> points;
    for (size_t i = 0; i < n; ++i) {
        const double a = 2.0 * 3.14159265358979323846 * double(i) / double(n);
        points.emplace_back(radius * std::cos(a), radius * std::sin(a));
    }
    return points;
}

TEST(ExtremeFootprints, DegenerateFootprintsAreCleanedOrSkippedWithAReason) {
    std::vector<glm::dvec2> clockwise = rectangle(16, 12);
    std::reverse(clockwise.begin(), clockwise.end());
    const std::vector<FootprintCase> cases{
        {"duplicate points", {{0, 0}, {0, 0}, {16, 0}, {16, 0}, {16, 12}, {0, 12}, {0, 12}}, true},
        {"collinear points", {{0, 0}, {8, 0}, {16, 0}, {16, 12}, {8, 12}, {0, 12}}, true},
        {"zero area", {{0, 0}, {16, 0}, {32, 0}}, false},
        {"a single point", {{5, 5}, {5, 5}, {5, 5}}, false},
        // A bow tie whose lobes differ is expanded (with a warning); a symmetric one has no area.
        {"bow tie", {{0, 0}, {16, 16}, {16, 0}, {0, 8}}, true},
        {"symmetric bow tie", {{0, 0}, {16, 12}, {16, 0}, {0, 12}}, false},
        {"counter-clockwise", rectangle(16, 12), true},
        {"clockwise", clockwise, true},
        {"10,000 vertices", circle(10000, 15.0), true},
        {"under 1 cm squared", rectangle(0.05, 0.05), true},
    };
    uint64_t counterClockwise = 0, reversed = 0;
    for (const FootprintCase& c : cases) {
        std::vector<grammar::BuildingInput> one{building(0, c.footprint)};
        const PipelineResult r = runPipeline(sceneOf("grammars/residential.grammar", std::move(one)),
                                             {lookAt({8, -40, 10}, {8, 6, 5}), false});
        EXPECT_EQ(r.terminals > 0, c.expands) << c.name;
        if (!c.expands) {
            ASSERT_FALSE(r.issues.empty()) << c.name;
            EXPECT_NE(r.issues.front().find("footprint"), std::string::npos)
                << c.name << ": " << r.issues.front();
        }
        EXPECT_TRUE(r.payloadsRoundTrip) << c.name;
        if (std::string(c.name) == "counter-clockwise") counterClockwise = r.terminals;
        if (std::string(c.name) == "clockwise") reversed = r.terminals;
    }
    // Winding is normalised: both give the same building.
    EXPECT_EQ(counterClockwise, reversed);
}

TEST(ExtremeFootprints, HolesInImportedFootprintsAreCountedAndTheOuterRingKept) {
    const auto path =
        std::filesystem::temp_directory_path() / ("hexlod-holes-" + std::to_string(::getpid()) + ".geojson");
    std::ofstream(path) << R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {},
      "geometry": {"type": "Polygon", "coordinates": [
        [[5.0, 52.0], [5.0004, 52.0], [5.0004, 52.0003], [5.0, 52.0003], [5.0, 52.0]],
        [[5.0001, 52.0001], [5.0002, 52.0001], [5.0002, 52.0002], [5.0001, 52.0002], [5.0001, 52.0001]]]}}]})";
    scene::ImportedFootprints imported;
    std::string error;
    ASSERT_TRUE(scene::readGeoJsonFootprints(path.string(), imported, error)) << error;
    ASSERT_EQ(imported.buildings.size(), 1u);
    EXPECT_GE(imported.buildings[0].footprint.size(), 4u); // the closing point is cleaned up later
    EXPECT_EQ(imported.holesIgnored, 1u);                  // reported, and the building kept
    EXPECT_TRUE(imported.skipped.empty());
    std::filesystem::remove(path);
}

} // namespace
} // namespace hexlod::extreme
