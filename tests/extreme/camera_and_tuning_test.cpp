// Extreme cases, part 3: odd cameras, LOD boundaries, and stiff parameter tuning.
#include "pipeline.h"

#include "hexlod/cells/scheduler.h"
#include "hexlod/impostor/view_lookup.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hexlod::extreme {
namespace {

std::vector<grammar::BuildingInput> street() {
    std::vector<grammar::BuildingInput> buildings;
    for (uint32_t i = 0; i < 8; ++i) buildings.push_back(building(i, rectangle(18.0, 14.0, {24.0 * i, 0.0})));
    return buildings;
}

TEST(ExtremeCameras, InsideABuildingOnAFacadePlaneAndAtExtremeFieldsOfView) {
    struct Case {
        const char* name;
        PipelineOptions options;
    };
    std::vector<Case> cases{
        {"inside a building", {lookAt({9, 7, 5}, {30, 7, 5}), true}},
        {"exactly on a facade plane", {lookAt({9, 0, 5}, {9, -10, 5}), true}},
        {"field of view 0.5 degrees", {lookAt({90, -300, 20}, {90, 7, 10}, 0.5), true}},
        {"field of view 179.5 degrees", {lookAt({90, -30, 20}, {90, 7, 10}, 179.5), true}},
        {"looking straight down", {lookAt({90, 7, 300}, {90, 7, 0}), true}},
    };
    PipelineOptions planes{lookAt({90, -60, 20}, {90, 7, 10}), true};
    planes.nearPlane = 1e-4;
    planes.farPlane = 1e7;
    cases.push_back({"near 1e-4 m and far 1e7 m", planes});
    PipelineOptions tiny{lookAt({90, -60, 20}, {90, 7, 10}), true, 1, 1};
    cases.push_back({"a 1 x 1 viewport", tiny});
    for (const Case& c : cases) {
        const PipelineResult r = runPipeline(sceneOf("grammars/residential.grammar", street()), c.options);
        EXPECT_TRUE(r.glClean) << c.name;
        EXPECT_TRUE(r.frameFinite) << c.name;
        EXPECT_FALSE(r.frame.empty()) << c.name;
    }
}

TEST(ExtremeCameras, GrazingAnglesToImpostorsKeepFiniteWeightsThatSumToOne) {
    impostor::ViewLayout layout;
    const impostor::ViewLookup lookup(layout);
    for (double angle : {89.0, 89.9, 89.999, 90.0, 90.001, 135.0, 180.0}) {
        const double a = angle * 3.14159265358979323846 / 180.0;
        impostor::ViewWeights w;
        ASSERT_TRUE(lookup.nearestViews(glm::vec3(std::sin(a), 0.0f, std::cos(a)), w)) << angle;
        float sum = 0.0f;
        for (float weight : w.weights) {
            EXPECT_TRUE(std::isfinite(weight)) << angle;
            sum += weight;
        }
        EXPECT_NEAR(sum, 1.0f, 1e-5f) << angle;
    }
}

TEST(ExtremeCameras, ACameraAtACornerOfThreeCellsSeesAllThree) {
    scene::BuiltScene built = sceneOf("grammars/residential.grammar", {}, 50.0);
    // Buildings around the corner where three hexagons of 50 m meet.
    const cells::HexGrid grid(50.0);
    const glm::dvec2 corner = grid.corners({0, 0})[0];
    // The three cells meeting at the corner lie 120 degrees apart around it, one of them
    // toward (0, 0)'s centre.
    const glm::dvec2 toCentre = glm::normalize(grid.center({0, 0}) - corner);
    const double c = std::cos(2.0943951), s = std::sin(2.0943951);
    const glm::dvec2 second(c * toCentre.x - s * toCentre.y, s * toCentre.x + c * toCentre.y);
    const glm::dvec2 third(c * second.x - s * second.y, s * second.x + c * second.y);
    uint32_t id = 0;
    for (cells::HexCoord cell :
         {cells::HexCoord{0, 0}, grid.cellOf(corner + 5.0 * second), grid.cellOf(corner + 5.0 * third)}) {
        const glm::dvec2 centre = grid.center(cell);
        built.buildingGrammars[0].buildings.push_back(
            building(id++, rectangle(10.0, 10.0, centre - glm::dvec2(5.0)),
                     built.buildingGrammars[0].grammar.defaultParameters()));
    }
    cells::BatchCatalog catalog(std::move(built));
    ASSERT_EQ(catalog.index().cells().size(), 3u);
    cache::TerminalSetCache cache(cache::CacheOptions{});
    cells::SchedulerOptions options;
    options.maxBatchesPerFrame = 0;
    cells::Scheduler scheduler(catalog, cache, options);
    cells::Camera camera;
    camera.position = glm::dvec3(corner, 400.0);
    camera.forward = glm::dvec3(0.0, 0.0001, -1.0);
    camera.fovY = 1.2;
    EXPECT_EQ(scheduler.update(camera, 0.0).cells.size(), 3u);
}

TEST(ExtremeCameras, ACameraHoveringAtTheLodBoundaryHoldsItsLodFor1000Frames) {
    scene::BuiltScene built = sceneOf("grammars/residential.grammar", street());
    cells::BatchCatalog catalog(std::move(built));
    cache::TerminalSetCache cache(cache::CacheOptions{});
    cells::SchedulerOptions options;
    options.maxBatchesPerFrame = 0;
    cells::Scheduler scheduler(catalog, cache, options);
    // The distance at which the extruded set's error equals the budget, and a camera that
    // oscillates 2 % around it.
    cells::Camera camera;
    camera.fovY = 1.0;
    const double boundary = options.lod.geometricError[1] * camera.viewportHeight /
                            (2.0 * std::tan(0.5 * camera.fovY) * options.lod.maxScreenSpaceError);
    const cells::CellBounds& cell = catalog.index().cells().front();
    const glm::dvec3 nearest(cell.lo.x, cell.lo.y, 0.0);
    uint32_t switches = 0;
    std::optional<cells::CellLod> previous;
    for (int frame = 0; frame < 1000; ++frame) {
        const double distance = boundary * (1.0 + 0.02 * std::sin(frame * 0.7));
        camera.position = nearest + glm::dvec3(-distance, 0.0, 0.0);
        camera.forward = glm::dvec3(1.0, 0.0, 0.0);
        const cells::FrameDecision decision = scheduler.update(camera, frame / 30.0);
        for (const cells::CellDecision& d : decision.cells) {
            if (d.cell != cell.cell) continue;
            if (previous && *previous != d.lod) ++switches;
            previous = d.lod;
        }
    }
    ASSERT_TRUE(previous.has_value());
    EXPECT_EQ(switches, 0u); // the 20 % hysteresis band holds a 2 % hover
}

TEST(ExtremeTuning, AThousandSmallEditsSweepAParameterAndLoseNothing) {
    std::vector<grammar::BuildingInput> buildings = street();
    cells::BatchCatalog catalog(sceneOf("grammars/residential.grammar", std::move(buildings)));
    cache::CacheOptions caching;
    caching.memoryBudgetBytes = uint64_t(8) << 20; // small, so old versions must age out
    cache::TerminalSetCache cache(caching);
    const grammar::CompiledGrammar& g = catalog.grammar(0).grammar;
    const grammar::ParameterInfo& floors = g.params[size_t(g.findParameter("floors"))];
    uint64_t previousTerminals = 0;
    for (int i = 0; i < 1000; ++i) {
        const double value = floors.minValue + (floors.maxValue - floors.minValue) * i / 999.0;
        const cells::EditResult edit = catalog.setParams(cells::BuildingIds{{3}}, {{"floors", value}});
        ASSERT_TRUE(edit.ok) << edit.error;
        uint64_t terminals = 0;
        for (uint32_t b = 0; b < catalog.batchCount(); ++b)
            terminals += catalog.fetch(b, cache)->records.size();
        // More storeys never mean fewer terminals in this grammar.
        EXPECT_GE(terminals, previousTerminals) << "edit " << i;
        previousTerminals = terminals;
        cache.trim();
        EXPECT_LE(cache.stats().memoryBytes, caching.memoryBudgetBytes + cache.stats().pinnedBytes)
            << "edit " << i;
    }
    EXPECT_EQ(catalog.historySize(), 1000u);
    const std::vector<float>& last = catalog.scene().buildingGrammars[0].buildings[3].parameters;
    EXPECT_FLOAT_EQ(last[size_t(g.findParameter("floors"))], floors.maxValue);
    EXPECT_GT(cache.stats().evictions, 0u); // old versions aged out instead of piling up
    RecordProperty("evictions", std::to_string(cache.stats().evictions));
    RecordProperty("terminals_at_max", std::to_string(previousTerminals));
}

} // namespace
} // namespace hexlod::extreme
