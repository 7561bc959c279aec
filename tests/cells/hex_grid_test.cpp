// Tests of the pointy-top hex grid (Red Blob Games conventions): hand-computed centres, corners
// and cells, point location at edges and corners, rings, region queries against brute force,
// and exactness 1e7 m from the origin.
#include "hexlod/cells/hex_grid.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <stdexcept>
#include <unordered_set>

namespace hexlod::cells {
namespace {

constexpr double kSqrt3 = 1.7320508075688772935;

void expectNear(glm::dvec2 actual, glm::dvec2 expected, double tolerance = 1e-9) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
}

double cross(glm::dvec2 a, glm::dvec2 b, glm::dvec2 p) {
    return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
}

// Sutherland-Hodgman: the part of `subject` inside the counter-clockwise convex `clip`; the
// subject may be degenerate.
std::vector<glm::dvec2> clipPolygon(std::vector<glm::dvec2> subject, const std::vector<glm::dvec2>& clip) {
    for (std::size_t i = 0; i < clip.size() && !subject.empty(); ++i) {
        const glm::dvec2 a = clip[i], b = clip[(i + 1) % clip.size()];
        std::vector<glm::dvec2> kept;
        for (std::size_t j = 0; j < subject.size(); ++j) {
            const glm::dvec2 p = subject[j], n = subject[(j + 1) % subject.size()];
            const double dp = cross(a, b, p), dn = cross(a, b, n);
            if (dp >= 0) kept.push_back(p);
            if ((dp >= 0) != (dn >= 0)) kept.push_back(p + (n - p) * (dp / (dp - dn)));
        }
        subject = std::move(kept);
    }
    return subject;
}

// Every cell whose hexagon overlaps the convex polygon (either winding), by clipping it with
// each hexagon near it: independent of the row walk and separating axes under test.
std::set<HexCoord> bruteForce(const HexGrid& grid, const std::vector<glm::dvec2>& polygon) {
    glm::dvec2 mid(0.0);
    for (glm::dvec2 p : polygon) mid += p / double(polygon.size());
    double reach = 0.0;
    for (glm::dvec2 p : polygon) reach = std::max(reach, glm::length(p - mid));
    const auto radius = static_cast<int32_t>(reach / grid.inradius()) + 2;
    std::set<HexCoord> out;
    for (HexCoord c : spiral(grid.cellOf(mid), radius)) {
        const auto corners = grid.corners(c);
        // The hexagon clips, so degenerate queries (a segment, a point) need no special case.
        if (!clipPolygon(polygon, {corners.begin(), corners.end()}).empty()) out.insert(c);
    }
    return out;
}

std::set<HexCoord> asSet(const std::vector<HexCoord>& cells) {
    return {cells.begin(), cells.end()};
}

// Rounds a local offset to what survives being added to a coordinate of 1e7 (multiples of
// 2^-29), so the same offset is exactly representable around a grid at (1e7, -1e7).
glm::dvec2 representableAtFarOrigin(glm::dvec2 p) {
    volatile double x = 1e7 + p.x, y = -1e7 + p.y; // volatile: keep the rounding step
    return {x - 1e7, y + 1e7};
}

TEST(HexCoord, CubeCoordinateOrderAndHash) {
    EXPECT_EQ((HexCoord{3, -5}.s()), 2);
    EXPECT_EQ((HexCoord{-4, 1}.s()), 3);
    EXPECT_TRUE((HexCoord{1, 2} == HexCoord{1, 2}));
    EXPECT_TRUE((HexCoord{1, 5} < HexCoord{2, -7})); // q first
    EXPECT_TRUE((HexCoord{1, -1} < HexCoord{1, 0}));
    const std::vector<HexCoord> disc = spiral({0, 0}, 20);
    const std::unordered_set<HexCoord> unique(disc.begin(), disc.end());
    EXPECT_EQ(unique.size(), 1261u); // 3 * 20 * 21 + 1
    EXPECT_NE(HexCoordHash{}({1, 0}), HexCoordHash{}({0, 1}));
}

TEST(HexGrid, CentresAndCornersHandComputed) {
    const HexGrid grid(100.0);
    EXPECT_DOUBLE_EQ(grid.circumradius(), 100.0);
    EXPECT_NEAR(grid.inradius(), 86.602540378443865, 1e-12);
    expectNear(grid.center({0, 0}), {0.0, 0.0});
    expectNear(grid.center({1, 0}), {173.20508075688772, 0.0});
    expectNear(grid.center({0, 1}), {86.602540378443865, 150.0});
    expectNear(grid.center({-2, 3}), {-86.602540378443865, 450.0});
    expectNear(grid.center({1, -1}), {86.602540378443865, -150.0});

    const auto c = grid.corners({0, 0});
    const glm::dvec2 expected[6] = {{86.602540378443865, -50.0}, {86.602540378443865, 50.0},   {0.0, 100.0},
                                    {-86.602540378443865, 50.0}, {-86.602540378443865, -50.0}, {0.0, -100.0}};
    for (int i = 0; i < 6; ++i) expectNear(c[i], expected[i]);
    expectNear(grid.corners({1, 1})[2], {259.80762113533160, 250.0});

    const HexGrid shifted(100.0, {1000.0, 2000.0});
    expectNear(shifted.center({0, 0}), {1000.0, 2000.0});
    expectNear(shifted.center({0, 1}), {1086.6025403784439, 2150.0});
    expectNear(shifted.localCenter({0, 1}), {86.602540378443865, 150.0});
}

TEST(HexGrid, CellOfHandComputedPoints) {
    const HexGrid grid(100.0);
    EXPECT_EQ(grid.cellOf({0.0, 0.0}), (HexCoord{0, 0}));
    EXPECT_EQ(grid.cellOf({80.0, 0.0}), (HexCoord{0, 0}));  // inradius 86.6
    EXPECT_EQ(grid.cellOf({90.0, 0.0}), (HexCoord{1, 0}));  // east of the vertical edge
    EXPECT_EQ(grid.cellOf({0.0, 99.0}), (HexCoord{0, 0}));  // below the top corner
    EXPECT_EQ(grid.cellOf({1.0, 101.0}), (HexCoord{0, 1})); // above it, east of x = 0
    EXPECT_EQ(grid.cellOf({-1.0, 101.0}), (HexCoord{-1, 1}));
    EXPECT_EQ(grid.cellOf({-300.0, -310.0}), (HexCoord{-1, -2})); // centre (-346.4, -300)
    // The documented tie rule on corners the arithmetic represents exactly.
    EXPECT_EQ(grid.cellOf({0.0, 100.0}), (HexCoord{0, 1}));
    EXPECT_EQ(grid.cellOf({0.0, -100.0}), (HexCoord{0, -1}));
    EXPECT_EQ(grid.cellOf({0.0, 400.0}), (HexCoord{-1, 3})); // top corner of (-1, 2)
}

TEST(HexGrid, CellOfRoundTripsCentres) {
    std::mt19937_64 rng(7);
    std::uniform_int_distribution<int32_t> coord(-1000000, 1000000);
    for (const HexGrid& grid : {HexGrid(100.0), HexGrid(0.37, {-5.0, 3.0}), HexGrid(2500.0, {1e7, -1e7})}) {
        for (int i = 0; i < 3000; ++i) {
            const HexCoord c{coord(rng), coord(rng)};
            ASSERT_EQ(grid.cellOf(grid.center(c)), c) << c.q << "," << c.r;
        }
    }
}

// Points 1e-6 m inside each edge (at a quarter, half and three quarters of it) stay in the
// cell; 1e-6 m outside they fall into the neighbour across that edge.
void checkEdges(const HexGrid& grid, HexCoord c) {
    const auto corners = grid.corners(c);
    const auto around = neighbours(c);
    const glm::dvec2 centre = grid.center(c);
    for (int i = 0; i < 6; ++i) {
        const glm::dvec2 a = corners[i], b = corners[(i + 1) % 6];
        const glm::dvec2 outward = glm::normalize((a + b) * 0.5 - centre);
        for (double t : {0.25, 0.5, 0.75}) {
            const glm::dvec2 p = a + (b - a) * t;
            EXPECT_EQ(grid.cellOf(p - outward * 1e-6), c) << "edge " << i << " t " << t;
            EXPECT_EQ(grid.cellOf(p + outward * 1e-6), around[i]) << "edge " << i << " t " << t;
        }
    }
}

TEST(HexGrid, EdgesSeparateACellFromTheRightNeighbour) {
    for (HexCoord c : {HexCoord{0, 0}, HexCoord{5, -3}, HexCoord{-40, 17}, HexCoord{123456, -654321}})
        checkEdges(HexGrid(100.0), c);
    checkEdges(HexGrid(100.0, {1e7, -1e7}), {3, -8});
    checkEdges(HexGrid(12.5, {-3.25e6, 7.5e5}), {-2, 9});
}

TEST(HexGrid, EveryPointLiesInExactlyOneCell) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-5000.0, 5000.0);
    for (const HexGrid& grid : {HexGrid(100.0), HexGrid(100.0, {1e7, -1e7})}) {
        for (int i = 0; i < 5000; ++i) {
            const glm::dvec2 p = grid.origin() + glm::dvec2(u(rng), u(rng));
            const HexCoord c = grid.cellOf(p);
            // The hexagons are the Voronoi cells of their centres: nothing is nearer than c's.
            const double own = glm::length(p - grid.center(c));
            for (HexCoord n : neighbours(c)) ASSERT_LE(own, glm::length(p - grid.center(n)) + 1e-9);
            const auto corners = grid.corners(c);
            for (int k = 0; k < 6; ++k) ASSERT_GE(cross(corners[k], corners[(k + 1) % 6], p), -1e-6);
        }
    }
}

TEST(HexGrid, FarOriginGivesTheSameCellsAsTheOrigin) {
    const HexGrid near(100.0);
    const HexGrid far(100.0, {1e7, -1e7});
    // Offsets from each cell centre: just inside and outside the edges, near corners, and the
    // exactly representable shared corners at x = 0 where the tie rule decides.
    std::vector<glm::dvec2> offsets;
    const glm::dvec2 half[3] = {{kSqrt3 * 50.0, -50.0}, {kSqrt3 * 50.0, 50.0}, {0.0, 100.0}};
    for (double sign : {1.0, -1.0})
        for (int i = 0; i < 3; ++i)
            for (double scale : {0.999999, 1.000001}) {
                offsets.push_back(sign * scale * half[i]); // corners
                // Edge midpoints, nudged across the edge either way.
                const glm::dvec2 mid = i < 2 ? (half[i] + half[i + 1]) * 0.5 : (half[2] - half[0]) * 0.5;
                offsets.push_back(sign * (1.0 + (scale - 1.0) * 0.01) * mid);
            }
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-120.0, 120.0);
    for (int i = 0; i < 200; ++i) offsets.push_back({u(rng), u(rng)});

    for (HexCoord c : {HexCoord{0, 0}, HexCoord{7, -2}, HexCoord{-3, 11}, HexCoord{-500, 250}}) {
        for (glm::dvec2 o : offsets) {
            const glm::dvec2 local = representableAtFarOrigin(near.localCenter(c) + o);
            const HexCoord expected = near.cellOf(local);
            ASSERT_EQ(far.cellOf(far.origin() + local), expected) << o.x << "," << o.y;
        }
    }
    // Corners at x = 0 are exact in both frames; the tie rule gives the same owners.
    for (HexCoord c : {HexCoord{0, 0}, HexCoord{-1, 2}, HexCoord{2, -4}}) {
        const glm::dvec2 top = near.localCenter(c) + glm::dvec2(0.0, 100.0);
        const glm::dvec2 bottom = near.localCenter(c) - glm::dvec2(0.0, 100.0);
        EXPECT_EQ(near.cellOf(top), neighbours(c)[1]);
        EXPECT_EQ(far.cellOf(far.origin() + top), neighbours(c)[1]);
        EXPECT_EQ(near.cellOf(bottom), neighbours(c)[4]);
        EXPECT_EQ(far.cellOf(far.origin() + bottom), neighbours(c)[4]);
    }
    const auto nearCells = near.cellsInRectangle({-333.3, -211.7}, {1234.5, 876.5});
    EXPECT_EQ(far.cellsInRectangle(far.origin() + glm::dvec2(-333.3, -211.7),
                                   far.origin() + glm::dvec2(1234.5, 876.5)),
              nearCells);
}

TEST(HexGrid, NeighboursAndDistance) {
    const std::array<HexCoord, 6> expected = {{{3, -1}, {2, 0}, {1, 0}, {1, -1}, {2, -2}, {3, -2}}};
    EXPECT_EQ(neighbours({2, -1}), expected);
    const HexGrid grid(10.0);
    const auto corners = grid.corners({2, -1});
    for (int i = 0; i < 6; ++i) {
        EXPECT_EQ(distance({2, -1}, expected[i]), 1);
        // Neighbour i mirrors the centre across edge i.
        const glm::dvec2 mid = (corners[i] + corners[(i + 1) % 6]) * 0.5;
        expectNear(grid.center(expected[i]), mid * 2.0 - grid.center({2, -1}));
    }
    EXPECT_EQ(distance({0, 0}, {0, 0}), 0);
    EXPECT_EQ(distance({0, 0}, {3, -5}), 5);
    EXPECT_EQ(distance({-2, 1}, {4, 3}), 8);
    EXPECT_EQ(distance({kMaxCoordinate, 0}, {-kMaxCoordinate, 0}), int64_t{2} * kMaxCoordinate);
}

TEST(HexGrid, RingsAndSpirals) {
    EXPECT_EQ(ring({4, -2}, 0), (std::vector<HexCoord>{{4, -2}}));
    EXPECT_EQ(ring({0, 0}, 1), (std::vector<HexCoord>{{0, -1}, {1, -1}, {1, 0}, {0, 1}, {-1, 1}, {-1, 0}}));
    const HexCoord centre{-7, 3};
    for (int32_t k = 1; k <= 12; ++k) {
        const auto cells = ring(centre, k);
        ASSERT_EQ(cells.size(), std::size_t(6 * k));
        EXPECT_EQ(asSet(cells).size(), cells.size());
        for (std::size_t i = 0; i < cells.size(); ++i) {
            EXPECT_EQ(distance(cells[i], centre), k);
            EXPECT_EQ(distance(cells[i], cells[(i + 1) % cells.size()]), 1); // a closed walk
        }
        const auto disc = spiral(centre, k);
        ASSERT_EQ(disc.size(), std::size_t(3 * k * (k + 1) + 1));
        EXPECT_EQ(disc.front(), centre);
        EXPECT_EQ(asSet(disc).size(), disc.size());
        for (HexCoord c : disc) EXPECT_LE(distance(c, centre), k);
    }
    EXPECT_EQ(spiral(centre, 0), (std::vector<HexCoord>{centre}));
}

TEST(HexGrid, RectangleHandComputed) {
    const HexGrid grid(100.0);
    EXPECT_EQ(grid.cellsInRectangle({-1.0, -1.0}, {1.0, 1.0}), (std::vector<HexCoord>{{0, 0}}));
    EXPECT_EQ(grid.cellsInRectangle({5.0, 5.0}, {5.0, 5.0}), (std::vector<HexCoord>{{0, 0}}));
    // Straddles the vertical edge x = 86.6 between (0, 0) and (1, 0).
    EXPECT_EQ(grid.cellsInRectangle({80.0, -1.0}, {90.0, 1.0}), (std::vector<HexCoord>{{0, 0}, {1, 0}}));
    // Reaches above y = 100 only near x = 0: the top corner's three cells, not (1, 0) or (0, -1).
    EXPECT_EQ(grid.cellsInRectangle({-1.0, 99.0}, {1.0, 101.0}),
              (std::vector<HexCoord>{{-1, 1}, {0, 0}, {0, 1}}));
    // Neither centre is near the rectangle, both hexagons reach into it: exact, not centres.
    const auto cells = grid.cellsInRectangle({100.0, 60.0}, {110.0, 70.0});
    EXPECT_EQ(cells, (std::vector<HexCoord>{{0, 1}, {1, 0}}));
}

TEST(HexGrid, RectangleMatchesBruteForce) {
    std::mt19937_64 rng(5);
    for (const HexGrid& grid : {HexGrid(100.0), HexGrid(37.0, {1e7, -1e7})}) {
        std::uniform_real_distribution<double> where(-2000.0, 2000.0), extent(0.0, 700.0);
        for (int i = 0; i < 300; ++i) {
            const glm::dvec2 lo = grid.origin() + glm::dvec2(where(rng), where(rng));
            const glm::dvec2 hi = lo + glm::dvec2(extent(rng), i % 10 == 0 ? 0.0 : extent(rng));
            const auto cells = grid.cellsInRectangle(lo, hi);
            ASSERT_TRUE(std::is_sorted(cells.begin(), cells.end()));
            ASSERT_EQ(asSet(cells), bruteForce(grid, {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}})) << i;
        }
    }
}

TEST(HexGrid, ConvexPolygonMatchesBruteForce) {
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (const HexGrid& grid : {HexGrid(50.0), HexGrid(80.0, {1e7, -1e7})}) {
        for (int i = 0; i < 300; ++i) {
            // Vertices at sorted angles on a rotated ellipse: convex and counter-clockwise.
            const glm::dvec2 centre = grid.origin() + glm::dvec2(unit(rng) - 0.5, unit(rng) - 0.5) * 3000.0;
            const double rx = 1.0 + 600.0 * unit(rng), ry = 1.0 + 300.0 * unit(rng), spin = 6.3 * unit(rng);
            std::vector<double> angles(3 + i % 8);
            for (double& a : angles) a = 6.283185307179586 * unit(rng);
            std::sort(angles.begin(), angles.end());
            std::vector<glm::dvec2> polygon;
            for (double a : angles) {
                const glm::dvec2 e(rx * std::cos(a), ry * std::sin(a));
                polygon.push_back(centre + glm::dvec2(e.x * std::cos(spin) - e.y * std::sin(spin),
                                                      e.x * std::sin(spin) + e.y * std::cos(spin)));
            }
            const auto cells = grid.cellsInConvexPolygon(polygon);
            ASSERT_EQ(asSet(cells), bruteForce(grid, polygon)) << i;
            const std::vector<glm::dvec2> clockwise(polygon.rbegin(), polygon.rend());
            ASSERT_EQ(grid.cellsInConvexPolygon(clockwise), cells);
        }
    }
    // A segment and a point are degenerate polygons the frustum footprint can produce.
    const HexGrid grid(100.0);
    const glm::dvec2 segment[2] = {{-1.0, 0.0}, {180.0, 0.0}};
    EXPECT_EQ(grid.cellsInConvexPolygon(segment), (std::vector<HexCoord>{{0, 0}, {1, 0}}));
    const glm::dvec2 point[1] = {{170.0, 10.0}};
    EXPECT_EQ(grid.cellsInConvexPolygon(point), (std::vector<HexCoord>{{1, 0}}));
}

TEST(HexGrid, AbsurdQueriesAreRefused) {
    const HexGrid grid(1.0);
    EXPECT_THROW(grid.cellsInRectangle({-1e9, -1e9}, {1e9, 1e9}), std::length_error);
    EXPECT_THROW(grid.cellsInRectangle({-1e12, 0.0}, {1e12, 0.0}), std::length_error);
    EXPECT_THROW(grid.cellsInRectangle({0.0, -1e12}, {0.0, 1e12}), std::length_error);
    EXPECT_THROW(grid.cellsInRectangle({1e300, 1e300}, {1e300, 1e300}), std::out_of_range);
    const glm::dvec2 huge[3] = {{0.0, 0.0}, {1e8, 0.0}, {0.0, 1e8}};
    EXPECT_THROW(grid.cellsInConvexPolygon(huge), std::length_error);
    EXPECT_THROW(grid.cellOf({1e300, 0.0}), std::out_of_range);
    EXPECT_THROW(ring({0, 0}, 1000000000), std::length_error);
    EXPECT_THROW(spiral({0, 0}, 100000), std::length_error);
    // Still fine just below the cap.
    EXPECT_EQ(grid.cellsInRectangle({0.0, 0.0}, {300.0, 300.0}).size() > 30000, true);
}

template <typename Exception, typename F> void expectThrowNaming(F f, const std::string& name) {
    try {
        f();
        ADD_FAILURE() << "no exception; expected one naming " << name;
    } catch (const Exception& e) {
        EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
}

TEST(HexGrid, InvalidInputsNameTheArgument) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    for (double bad : {0.0, -5.0, nan, inf, -inf, std::numeric_limits<double>::max()})
        expectThrowNaming<std::invalid_argument>([&] { HexGrid g(bad); }, "circumradius");
    expectThrowNaming<std::invalid_argument>([&] { HexGrid g(1.0, {nan, 0.0}); }, "origin");
    expectThrowNaming<std::invalid_argument>([&] { HexGrid g(1.0, {0.0, inf}); }, "origin");

    const HexGrid grid(10.0);
    expectThrowNaming<std::invalid_argument>([&] { grid.cellOf({nan, 0.0}); }, "world");
    expectThrowNaming<std::invalid_argument>([&] { grid.cellOf({0.0, -inf}); }, "world");
    expectThrowNaming<std::invalid_argument>([&] { grid.cellsInRectangle({nan, 0.0}, {1.0, 1.0}); }, "lo");
    expectThrowNaming<std::invalid_argument>([&] { grid.cellsInRectangle({0.0, 0.0}, {inf, 1.0}); }, "hi");
    expectThrowNaming<std::invalid_argument>([&] { grid.cellsInRectangle({2.0, 0.0}, {1.0, 1.0}); }, "lo");
    expectThrowNaming<std::invalid_argument>([&] { grid.cellsInConvexPolygon({}); }, "points");
    const glm::dvec2 badPolygon[2] = {{0.0, 0.0}, {nan, 1.0}};
    expectThrowNaming<std::invalid_argument>([&] { grid.cellsInConvexPolygon(badPolygon); }, "points");
    expectThrowNaming<std::invalid_argument>([&] { ring({0, 0}, -1); }, "radius");
    expectThrowNaming<std::invalid_argument>([&] { spiral({0, 0}, -3); }, "radius");
}

} // namespace
} // namespace hexlod::cells
