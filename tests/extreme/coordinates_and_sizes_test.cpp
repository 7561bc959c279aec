// Extreme cases, part 1: far coordinates and scope sizes (docs/ROBUSTNESS.md lists each case
// with its expected behaviour).
#include "pipeline.h"

#include "hexlod/render/image_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>

namespace hexlod::extreme {
namespace {

// World positions of every terminal, from the batch's cell origin (double) and the record, per
// (building, shape) in derivation order: the far city falls into other cells, so batches differ.
std::map<std::pair<uint32_t, uint32_t>, std::vector<glm::dvec3>>
worldPositions(const scene::BuiltScene& built) {
    cells::BatchCatalog catalog(built);
    std::map<std::pair<uint32_t, uint32_t>, std::vector<glm::dvec3>> out;
    for (uint32_t b = 0; b < catalog.batchCount(); ++b) {
        const grammar::TerminalSet set = catalog.generate(b);
        const glm::dvec3 origin(set.header.cellOrigin[0], set.header.cellOrigin[1], set.header.cellOrigin[2]);
        for (const auto& r : set.records)
            out[{r.building, r.shapeAndDepth & 0xffffu}].push_back(
                origin + glm::dvec3(r.position[0], r.position[1], r.position[2]));
    }
    return out;
}

std::vector<grammar::BuildingInput> block(glm::dvec2 offset) {
    std::vector<grammar::BuildingInput> buildings;
    for (uint32_t i = 0; i < 6; ++i)
        buildings.push_back(building(i, rectangle(18.0, 14.0, offset + glm::dvec2(30.0 * i, 0.0))));
    return buildings;
}

TEST(ExtremeCoordinates, ACity1e7MetresOutMatchesTheOriginWithinAMillimetreAndRendersAlike) {
    const glm::dvec2 far(1e7, -1e7);
    const scene::BuiltScene near = sceneOf("grammars/residential.grammar", block({0, 0}));
    const scene::BuiltScene away = sceneOf("grammars/residential.grammar", block(far));
    const auto a = worldPositions(near), b = worldPositions(away);
    ASSERT_EQ(a.size(), b.size());
    double worst = 0.0;
    size_t compared = 0;
    for (const auto& [key, positions] : a) {
        const std::vector<glm::dvec3>& other = b.at(key);
        ASSERT_EQ(other.size(), positions.size());
        for (size_t i = 0; i < positions.size(); ++i, ++compared)
            worst = std::max(worst, glm::length(other[i] - glm::dvec3(far, 0.0) - positions[i]));
    }
    ASSERT_GT(compared, 1000u);
    EXPECT_LT(worst, 1e-3) << "worst terminal offset " << worst << " m";
    RecordProperty("worst_offset_m", std::to_string(worst)); // for docs/ROBUSTNESS.md
    RecordProperty("terminals_compared", std::to_string(compared));

    PipelineOptions options;
    options.camera = lookAt({80, -60, 25}, {80, 7, 8});
    PipelineOptions farOptions = options;
    farOptions.camera.position += glm::dvec3(far, 0.0);
    const PipelineResult x = runPipeline(near, options), y = runPipeline(away, farOptions);
    EXPECT_TRUE(x.payloadsRoundTrip && y.payloadsRoundTrip);
    EXPECT_EQ(x.cull.terminalsPerLod, y.cull.terminalsPerLod);
    // The stated bound: the two frames agree to 40 dB (they differ by float rounding only).
    const double psnr = render::compareImages(x.frame, y.frame).psnr;
    EXPECT_GE(psnr, 40.0);
    RecordProperty("frame_psnr_db", std::to_string(psnr));
    EXPECT_TRUE(x.glClean && y.glClean);
}

TEST(ExtremeScopeSizes, FacadesFromAMillimetreToTenKilometresExpandAndRender) {
    for (double width : {0.001, 0.01, 1.0, 100.0, 10000.0}) {
        std::vector<grammar::BuildingInput> one{building(0, rectangle(width, 12.0))};
        const PipelineResult r = runPipeline(sceneOf("grammars/residential.grammar", std::move(one), 2000.0),
                                             {lookAt({width / 2, -40, 10}, {width / 2, 0, 5}), true});
        EXPECT_FALSE(r.failedBatch) << width;
        EXPECT_TRUE(r.payloadsRoundTrip) << width;
        EXPECT_TRUE(r.glClean && r.frameFinite) << width;
        if (width >= 1.0) {
            EXPECT_GT(r.terminals, 0u) << width;
        }
        // A 10 km facade holds thousands of window bays per storey, all of them terminals.
        if (width == 10000.0) {
            EXPECT_GT(r.terminals, 20000u);
            RecordProperty("terminals_of_10km_facade", std::to_string(r.terminals));
        }
    }
}

// A grammar whose Split and Repeat sizes come from one parameter, so each extreme value goes
// through both rules.
std::string sizedGrammar(const std::string& split, const std::string& repeat) {
    return "param s = 1 in [-1e30, 1e30];\nshape tile(triangles = 2);\nLot -> Extrude(9) { Facade, NULL };\n"
           "Facade -> Split(y, " +
           split + ") { Row, Row, Row };\nRow -> Repeat(x, " + repeat +
           ", fit) { Tile };\n"
           "Tile -> Shape(tile);\n";
}

TEST(ExtremeScopeSizes, DegenerateSplitAndRepeatSizesAreReportedNotFatal) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    struct Case {
        const char* name;
        float value;
        bool reported; // an InvalidSize / TooManyTiles issue names the rule
    };
    for (const Case& c : {Case{"tending to 0", 1e-30f, true}, Case{"negative", -2.0f, true},
                          Case{"NaN", nan, true}, Case{"infinite", inf, true},
                          Case{"larger than the scope", 1e6f, false}, Case{"ordinary", 1.5f, false}}) {
        std::vector<grammar::BuildingInput> one{building(0, rectangle(12.0, 8.0), {c.value})};
        const PipelineResult r = runPipeline(sceneOf(sizedGrammar("s, ~1, s", "s"), std::move(one)),
                                             {lookAt({6, -30, 5}, {6, 0, 4}), false});
        EXPECT_FALSE(r.failedBatch) << c.name;
        EXPECT_TRUE(r.payloadsRoundTrip) << c.name;
        EXPECT_EQ(!r.issues.empty(), c.reported)
            << c.name << ": " << (r.issues.empty() ? "" : r.issues.front());
        for (const std::string& issue : r.issues)
            EXPECT_NE(issue.find("extreme.grammar:"), std::string::npos) << issue;
    }
}

TEST(ExtremeScopeSizes, PartsSummingPastTheScopeAndRelativeWeightsSummingToZero) {
    // Absolute parts of 9 + 9 in a 9 m facade are scaled to fit; relative weights of 0 get nothing.
    std::vector<grammar::BuildingInput> one{building(0, rectangle(12.0, 8.0), {9.0f})};
    const PipelineResult past = runPipeline(sceneOf(sizedGrammar("s, ~0, s", "1.5"), std::move(one)),
                                            {lookAt({6, -30, 5}, {6, 0, 4}), false});
    EXPECT_FALSE(past.failedBatch);
    EXPECT_GT(past.terminals, 0u);
    std::vector<grammar::BuildingInput> zero{building(0, rectangle(12.0, 8.0), {0.0f})};
    const PipelineResult weights = runPipeline(sceneOf(sizedGrammar("~s, ~s, ~s", "1.5"), std::move(zero)),
                                               {lookAt({6, -30, 5}, {6, 0, 4}), false});
    EXPECT_EQ(weights.terminals, 0u); // every part has size 0, so there are no rows
    EXPECT_FALSE(weights.failedBatch);
}

} // namespace
} // namespace hexlod::extreme
