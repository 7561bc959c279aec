#include "hexlod/scene/city_generator.h"

#include "hexlod/grammar/footprint.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace hexlod::scene {
namespace {

using Polygon = std::vector<glm::dvec2>;

CityOptions twoDistricts(uint32_t buildings, uint32_t trees, uint64_t seed = 1) {
    CityOptions o;
    o.seed = seed;
    o.buildings = buildings;
    o.trees = trees;
    o.districts = {{"business", 0.3, 8.0, 30.0, 30.0, 35.0}, {"residential", 0.7, 2.0, 5.0, 18.0, 25.0}};
    return o;
}

struct Box {
    glm::dvec2 lo, hi;
};

Box boundsOf(const Polygon& p) {
    Box b{p[0], p[0]};
    for (const glm::dvec2& q : p) b.lo = glm::min(b.lo, q), b.hi = glm::max(b.hi, q);
    return b;
}

double cross(glm::dvec2 a, glm::dvec2 b) {
    return a.x * b.y - a.y * b.x;
}

// Proper crossings and touches alike count: footprints must keep apart.
bool segmentsMeet(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, glm::dvec2 d) {
    const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
    const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
    if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
    auto within = [](glm::dvec2 p, glm::dvec2 q, glm::dvec2 r) {
        return std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) && std::min(p.y, q.y) <= r.y &&
               r.y <= std::max(p.y, q.y);
    };
    return (d1 == 0 && within(a, b, c)) || (d2 == 0 && within(a, b, d)) || (d3 == 0 && within(c, d, a)) ||
           (d4 == 0 && within(c, d, b));
}

bool contains(const Polygon& poly, glm::dvec2 p) {
    bool inside = false;
    for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
        const glm::dvec2 a = poly[i], b = poly[j];
        if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x))
            inside = !inside;
    }
    return inside;
}

bool polygonsOverlap(const Polygon& p, const Polygon& q) {
    for (size_t i = 0; i < p.size(); ++i)
        for (size_t j = 0; j < q.size(); ++j)
            if (segmentsMeet(p[i], p[(i + 1) % p.size()], q[j], q[(j + 1) % q.size()])) return true;
    return contains(p, q[0]) || contains(q, p[0]);
}

double distanceToSegment(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b) {
    const glm::dvec2 ab = b - a;
    const double t = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
    return glm::length(p - (a + t * ab));
}

glm::dvec2 centroidOf(const Polygon& p) {
    glm::dvec2 sum(0.0);
    for (const glm::dvec2& q : p) sum += q;
    return sum / static_cast<double>(p.size());
}

// More than four corners, or a corner that is not a right angle.
bool nonRectangular(const Polygon& p) {
    if (p.size() > 4) return true;
    for (size_t i = 0; i < p.size(); ++i) {
        const glm::dvec2 e1 = glm::normalize(p[(i + 1) % p.size()] - p[i]);
        const glm::dvec2 e2 = glm::normalize(p[(i + 2) % p.size()] - p[(i + 1) % p.size()]);
        if (std::abs(glm::dot(e1, e2)) > 1e-6) return true;
    }
    return false;
}

void expectCounts(const CityOptions& options) {
    const GeneratedCity city = generateCity(options);
    ASSERT_EQ(city.buildings.size(), options.buildings);
    ASSERT_EQ(city.trees.size(), options.trees);
    for (uint32_t id = 0; id < city.buildings.size(); ++id) EXPECT_EQ(city.buildings[id].input.id, id);
}

TEST(CityGenerator, ExactCountsAndIds) {
    expectCounts(twoDistricts(500, 2000));
    expectCounts(twoDistricts(37, 0));
    expectCounts(twoDistricts(0, 300));
    expectCounts(twoDistricts(10000, 48000));
    CityOptions single = twoDistricts(1234, 5);
    single.districts.resize(1);
    expectCounts(single);
}

TEST(CityGenerator, ZeroBuildingsAndTreesIsAnEmptyCity) {
    const GeneratedCity city = generateCity(twoDistricts(0, 0));
    EXPECT_TRUE(city.buildings.empty());
    EXPECT_TRUE(city.trees.empty());
    EXPECT_TRUE(city.roads.empty());
}

TEST(CityGenerator, TreesWithoutBuildingsStillLineStreets) {
    const GeneratedCity city = generateCity(twoDistricts(0, 300));
    EXPECT_TRUE(city.buildings.empty());
    EXPECT_FALSE(city.roads.empty());
    EXPECT_EQ(city.trees.size(), 300u);
}

TEST(CityGenerator, FootprintsAreCleanAndVaried) {
    const GeneratedCity city = generateCity(twoDistricts(3000, 0));
    size_t varied = 0;
    for (const GeneratedBuilding& b : city.buildings) {
        grammar::CleanFootprint clean;
        std::string error;
        ASSERT_TRUE(grammar::cleanFootprint(b.input.footprint, clean, error))
            << "building " << b.input.id << error;
        EXPECT_FALSE(clean.selfIntersecting) << "building " << b.input.id;
        EXPECT_FALSE(clean.reversed) << "building " << b.input.id;
        EXPECT_EQ(clean.removedPoints, 0u) << "building " << b.input.id;
        EXPECT_GT(clean.area, 10.0) << "building " << b.input.id;
        varied += nonRectangular(clean.points);
    }
    EXPECT_GE(varied, city.buildings.size() / 5);
    EXPECT_LE(varied, city.buildings.size() * 4 / 5);
}

TEST(CityGenerator, FootprintsDoNotOverlap) {
    const Polygon square{{0, 0}, {2, 0}, {2, 2}, {0, 2}};
    ASSERT_TRUE(polygonsOverlap(square, {{1, 1}, {3, 1}, {3, 3}, {1, 3}}));
    ASSERT_TRUE(polygonsOverlap(square, {{0.5, 0.5}, {1, 0.5}, {1, 1}}));
    ASSERT_FALSE(polygonsOverlap(square, {{2.5, 0}, {4, 0}, {4, 2}}));

    const GeneratedCity city = generateCity(twoDistricts(2000, 0, 7));
    std::vector<std::pair<Box, uint32_t>> boxes;
    for (const GeneratedBuilding& b : city.buildings)
        boxes.push_back({boundsOf(b.input.footprint), b.input.id});
    std::sort(boxes.begin(), boxes.end(),
              [](const auto& a, const auto& b) { return a.first.lo.x < b.first.lo.x; });
    // Neighbours within a few metres get the exact polygon test; the boxes themselves must
    // not even overlap, as every footprint keeps to its own lot.
    const double reach = 6.0;
    size_t neighbours = 0;
    for (size_t i = 0; i < boxes.size(); ++i) {
        for (size_t j = i + 1; j < boxes.size() && boxes[j].first.lo.x <= boxes[i].first.hi.x + reach; ++j) {
            const Box &a = boxes[i].first, &b = boxes[j].first;
            if (a.hi.y + reach < b.lo.y || b.hi.y + reach < a.lo.y) continue;
            ++neighbours;
            const uint32_t p = boxes[i].second, q = boxes[j].second;
            const bool boxesMeet =
                a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y;
            EXPECT_FALSE(boxesMeet) << "buildings " << p << " and " << q;
            EXPECT_FALSE(
                polygonsOverlap(city.buildings[p].input.footprint, city.buildings[q].input.footprint))
                << "buildings " << p << " and " << q;
        }
    }
    EXPECT_GT(neighbours, city.buildings.size() / 2);
}

TEST(CityGenerator, FootprintsKeepOffTheRoads) {
    const CityOptions options = twoDistricts(300, 0, 3);
    const GeneratedCity city = generateCity(options);
    ASSERT_FALSE(city.roads.empty());
    for (const RoadSegment& road : city.roads) EXPECT_EQ(road.width, options.streetWidth);
    for (const GeneratedBuilding& b : city.buildings) {
        for (const glm::dvec2& p : b.input.footprint) {
            EXPECT_TRUE(glm::all(glm::greaterThan(p, city.extentMin)) &&
                        glm::all(glm::lessThan(p, city.extentMax)))
                << "building " << b.input.id;
            for (const RoadSegment& road : city.roads)
                ASSERT_GT(distanceToSegment(p, road.a, road.b), 0.5 * options.streetWidth)
                    << "building " << b.input.id;
        }
    }
}

TEST(CityGenerator, StreetTreesStandOnThePavement) {
    const CityOptions options = twoDistricts(300, 1500, 3);
    const GeneratedCity city = generateCity(options);
    for (const TreeInstance& t : city.trees) {
        if (t.inPark) continue;
        double nearest = INFINITY;
        for (const RoadSegment& road : city.roads)
            nearest = std::min(nearest, distanceToSegment(t.position, road.a, road.b));
        EXPECT_LT(nearest, 0.5 * options.streetWidth);
        EXPECT_GT(nearest, 0.25 * options.streetWidth);
    }
}

TEST(CityGenerator, DistrictsRingTheCentreWithTheirFloorRanges) {
    const CityOptions options = twoDistricts(10000, 0);
    const GeneratedCity city = generateCity(options);
    double distance[2] = {0, 0}, count[2] = {0, 0};
    double innerFloors = 0, outerFloors = 0, inner = 0, outer = 0;
    double businessRadius = 0;
    for (const GeneratedBuilding& b : city.buildings) {
        ASSERT_LT(b.district, 2u);
        const DistrictSpec& spec = options.districts[b.district];
        EXPECT_GE(b.floors, spec.minFloors);
        EXPECT_LE(b.floors, spec.maxFloors);
        const double d = glm::length(centroidOf(b.input.footprint));
        distance[b.district] += d;
        count[b.district] += 1;
        if (b.district == 0) businessRadius = std::max(businessRadius, d);
    }
    ASSERT_GT(count[0], 500);
    ASSERT_GT(count[1], 500);
    EXPECT_LT(distance[0] / count[0], 0.6 * distance[1] / count[1]);
    // Within the business district, towers rise towards the centre.
    for (const GeneratedBuilding& b : city.buildings) {
        if (b.district != 0) continue;
        const bool central = glm::length(centroidOf(b.input.footprint)) < 0.5 * businessRadius;
        (central ? innerFloors : outerFloors) += b.floors;
        (central ? inner : outer) += 1;
    }
    EXPECT_GT(innerFloors / inner, outerFloors / outer + 2.0);
}

TEST(CityGenerator, ParksHoldTreesAndNoBuildings) {
    CityOptions options = twoDistricts(2000, 10000);
    options.parkShare = 0.2;
    const GeneratedCity city = generateCity(options);
    ASSERT_GE(city.parks.size(), 5u);
    for (const Polygon& park : city.parks) {
        size_t trees = 0;
        for (const TreeInstance& t : city.trees) trees += t.inPark && contains(park, t.position);
        EXPECT_GT(trees, 0u);
        for (const GeneratedBuilding& b : city.buildings)
            for (const glm::dvec2& p : b.input.footprint) ASSERT_FALSE(contains(park, p));
    }
    size_t streetTrees = 0;
    for (const TreeInstance& t : city.trees) {
        EXPECT_LT(t.species, options.species);
        EXPECT_GE(t.scale, 0.7f);
        EXPECT_LE(t.scale, 1.3f);
        streetTrees += !t.inPark;
    }
    EXPECT_GT(streetTrees, city.trees.size() / 2);
}

bool sameCity(const GeneratedCity& a, const GeneratedCity& b) {
    if (a.buildings.size() != b.buildings.size() || a.trees.size() != b.trees.size()) return false;
    for (size_t i = 0; i < a.buildings.size(); ++i) {
        const Polygon &p = a.buildings[i].input.footprint, &q = b.buildings[i].input.footprint;
        if (p.size() != q.size() || std::memcmp(p.data(), q.data(), p.size() * sizeof(glm::dvec2)) != 0)
            return false;
        if (a.buildings[i].floors != b.buildings[i].floors ||
            a.buildings[i].district != b.buildings[i].district)
            return false;
    }
    for (size_t i = 0; i < a.trees.size(); ++i) {
        if (a.trees[i].position != b.trees[i].position || a.trees[i].species != b.trees[i].species)
            return false;
    }
    return true;
}

TEST(CityGenerator, SameOptionsSameCityOtherSeedOtherCity) {
    const GeneratedCity a = generateCity(twoDistricts(800, 3000, 11));
    EXPECT_TRUE(sameCity(a, generateCity(twoDistricts(800, 3000, 11))));
    EXPECT_FALSE(sameCity(a, generateCity(twoDistricts(800, 3000, 12))));
}

TEST(CityGenerator, ThesisScale) {
    CityOptions options = twoDistricts(116573, 561280);
    const GeneratedCity city = generateCity(options);
    EXPECT_EQ(city.buildings.size(), 116573u);
    EXPECT_EQ(city.trees.size(), 561280u);
    EXPECT_EQ(city.buildings.back().input.id, 116572u);
    EXPECT_GT(city.extentMax.x - city.extentMin.x, 5000.0);
}

void expectRejected(CityOptions options, const std::string& option) {
    try {
        generateCity(options);
        ADD_FAILURE() << "accepted bad " << option;
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find(option), std::string::npos) << e.what();
    }
}

TEST(CityGenerator, InvalidOptionsNameTheOption) {
    CityOptions o = twoDistricts(10, 10);
    o.districts.clear();
    expectRejected(o, "districts");
    o = twoDistricts(10, 10);
    o.blockSize = std::nan("");
    expectRejected(o, "blockSize");
    o.blockSize = -5.0;
    expectRejected(o, "blockSize");
    o = twoDistricts(10, 10);
    o.streetWidth = 0.0;
    expectRejected(o, "streetWidth");
    o = twoDistricts(10, 10);
    o.parkShare = 0.95;
    expectRejected(o, "parkShare");
    o.parkShare = -0.1;
    expectRejected(o, "parkShare");
    o = twoDistricts(10, 10);
    o.districts[1].lotWidth = INFINITY;
    expectRejected(o, "lotWidth");
    o = twoDistricts(10, 10);
    o.districts[0].lotDepth = 0.0;
    expectRejected(o, "lotDepth");
    o = twoDistricts(10, 10);
    o.districts[1].minFloors = 9.0;
    expectRejected(o, "minFloors");
    o = twoDistricts(10, 10);
    o.species = 0;
    expectRejected(o, "species");
}

} // namespace
} // namespace hexlod::scene
