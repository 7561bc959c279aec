// Tests of the camera frustum: hand-computed planes and corners, conservative box and prism
// tests against sampled points, the slab footprint, and the cells a street camera sees.
#include "hexlod/cells/frustum.h"
#include "hexlod/cells/hex_grid.h"

#include <gtest/gtest.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <set>
#include <stdexcept>

namespace hexlod::cells {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

void expectNear(glm::dvec3 actual, glm::dvec3 expected, double tolerance = 1e-9) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

// Looking east (+x) from the origin, z up: right is -y. 90 degrees vertical, aspect 2.
Frustum eastCamera() {
    return Frustum({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, 90.0 * kDegree, 2.0, 1.0, 10.0);
}

TEST(Frustum, PlanesAndCornersHandComputed) {
    const Frustum f = eastCamera();
    const auto c = f.corners();
    expectNear(c[0], {1.0, 2.0, -1.0}); // near bottom-left
    expectNear(c[1], {1.0, -2.0, -1.0});
    expectNear(c[2], {1.0, -2.0, 1.0});
    expectNear(c[3], {1.0, 2.0, 1.0});
    expectNear(c[6], {10.0, -20.0, 10.0}); // far top-right
    expectNear(f.planes()[Frustum::Near].normal, {1.0, 0.0, 0.0});
    EXPECT_DOUBLE_EQ(f.planes()[Frustum::Near].offset, -1.0);
    expectNear(f.planes()[Frustum::Far].normal, {-1.0, 0.0, 0.0});
    expectNear(f.planes()[Frustum::Top].normal, glm::dvec3(1.0, 0.0, -1.0) / std::sqrt(2.0));
    expectNear(f.planes()[Frustum::Left].normal, glm::dvec3(2.0, -1.0, 0.0) / std::sqrt(5.0));

    EXPECT_TRUE(f.contains({5.0, 0.0, 0.0}));
    EXPECT_TRUE(f.contains({5.0, 9.9, 4.9}));
    EXPECT_FALSE(f.contains({0.5, 0.0, 0.0}));  // before the near plane
    EXPECT_FALSE(f.contains({10.5, 0.0, 0.0})); // beyond the far plane
    EXPECT_FALSE(f.contains({5.0, 10.5, 0.0})); // left of |y| <= 2x
    EXPECT_FALSE(f.contains({5.0, 0.0, -5.5})); // below |z| <= x
}

TEST(Frustum, BoxTests) {
    const Frustum f = eastCamera();
    EXPECT_TRUE(f.intersectsBox({4.0, -1.0, -1.0}, {6.0, 1.0, 1.0}));              // inside
    EXPECT_TRUE(f.intersectsBox({-100.0, -100.0, -100.0}, {100.0, 100.0, 100.0})); // encloses it
    EXPECT_TRUE(f.intersectsBox({5.0, -50.0, -0.1}, {5.1, 50.0, 0.1}));  // crosses, no corner inside
    EXPECT_FALSE(f.intersectsBox({-3.0, -1.0, -1.0}, {-2.0, 1.0, 1.0})); // behind the eye
    EXPECT_FALSE(f.intersectsBox({11.0, -1.0, -1.0}, {12.0, 1.0, 1.0})); // beyond far
    // Near the far-left edge: no single plane has all box corners outside, but all frustum
    // corners have y < 21; only the corners-versus-box-axes refinement culls it.
    EXPECT_FALSE(f.intersectsBox({9.0, 21.0, -2.0}, {13.0, 25.0, 2.0}));
}

TEST(Frustum, PrismTestIsConservativeAgainstSampledPoints) {
    std::mt19937_64 rng(21);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int visible = 0, culled = 0;
    for (int i = 0; i < 200; ++i) {
        const double yaw = 6.283 * unit(rng), pitch = (unit(rng) - 0.7) * 1.5;
        const glm::dvec3 forward(std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw),
                                 std::sin(pitch));
        const Frustum f({0.0, 0.0, 2.0 + 30.0 * unit(rng)}, forward, {0.0, 0.0, 1.0},
                        (5.0 + 120.0 * unit(rng)) * kDegree, 0.5 + 2.0 * unit(rng), 0.5,
                        50.0 + 200.0 * unit(rng));
        for (int k = 0; k < 20; ++k) {
            const glm::dvec2 centre((unit(rng) - 0.5) * 500.0, (unit(rng) - 0.5) * 500.0);
            const double size = 5.0 + 40.0 * unit(rng), zMin = -5.0 + 10.0 * unit(rng),
                         zMax = zMin + 40.0 * unit(rng);
            const HexGrid shape(size, centre);
            bool seen = false;
            for (int s = 0; s < 400 && !seen; ++s) {
                const glm::dvec2 p = centre + glm::dvec2(unit(rng) - 0.5, unit(rng) - 0.5) * (2.0 * size);
                if (shape.cellOf(p) != HexCoord{0, 0}) continue; // outside the hexagon
                seen = f.contains({p.x, p.y, zMin + (zMax - zMin) * unit(rng)});
            }
            const bool kept = f.intersectsPrism(centre, size, zMin, zMax);
            ASSERT_TRUE(!seen || kept) << i << " " << k;
            visible += seen;
            culled += !kept;
        }
    }
    EXPECT_GT(visible, 100); // the sampling found visible prisms...
    EXPECT_GT(culled, 100);  // ...and the test culls many others
}

TEST(Frustum, FootprintOfADownwardCamera) {
    // From 100 m straight down with 90 degrees: the ground square is +-100 m, the slab top at
    // z = 10 gives +-90 m, so the footprint is the ground square.
    const Frustum f({0.0, 0.0, 100.0}, {0.0, 0.0, -1.0}, {0.0, 1.0, 0.0}, 90.0 * kDegree, 1.0, 1.0, 200.0);
    const auto footprint = f.footprint(0.0, 10.0);
    ASSERT_EQ(footprint.size(), 4u);
    const std::set<std::pair<double, double>> corners(
        {{-100.0, -100.0}, {100.0, -100.0}, {100.0, 100.0}, {-100.0, 100.0}});
    for (glm::dvec2 p : footprint) {
        const std::pair<double, double> rounded(std::round(p.x * 1e6) / 1e6, std::round(p.y * 1e6) / 1e6);
        EXPECT_TRUE(corners.count(rounded)) << p.x << "," << p.y;
    }
    EXPECT_TRUE(f.footprint(150.0, 160.0).empty());   // above the eye
    EXPECT_TRUE(f.footprint(-200.0, -150.0).empty()); // beyond the far plane
}

// Standing at the centre of cell (0, 0), eye 1.7 m up, looking east along row r = 0 with
// 10 degrees vertical and horizontal field (|y| <= 0.0875 x) and a 600 m far plane. Row 0 has
// its full width for |y| <= 50, rows +-1 start at |y| = 50 and the wedge reaches only
// 52.5 m, where their hexagons lie beyond 600 m; (4, 0) starts at x = 606.2.
std::vector<HexCoord> streetCells(glm::dvec2 origin) {
    const HexGrid grid(100.0, origin);
    const Frustum f({origin.x, origin.y, 1.7}, {1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, 10.0 * kDegree, 1.0, 0.5,
                    600.0);
    return grid.cellsInFrustum(f, 0.0, 20.0);
}

TEST(Frustum, StreetCameraSeesItsRow) {
    const std::vector<HexCoord> expected = {{0, 0}, {1, 0}, {2, 0}, {3, 0}};
    EXPECT_EQ(streetCells({0.0, 0.0}), expected);
    EXPECT_EQ(streetCells({1e7, -1e7}), expected);
}

TEST(Frustum, CellsInFrustumNeverMissesAVisiblePoint) {
    std::mt19937_64 rng(33);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (const glm::dvec2 origin : {glm::dvec2(0.0, 0.0), glm::dvec2(1e7, -1e7)}) {
        const HexGrid grid(40.0, origin);
        const double zMin = 0.0, zMax = 35.0;
        for (int i = 0; i < 60; ++i) {
            const double yaw = 6.283 * unit(rng), pitch = (unit(rng) - 0.8) * 1.2;
            const glm::dvec3 eye(origin.x + 300.0 * (unit(rng) - 0.5), origin.y + 300.0 * (unit(rng) - 0.5),
                                 1.0 + 80.0 * unit(rng));
            const glm::dvec3 forward(std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw),
                                     std::sin(pitch));
            const double fovY = (10.0 + 100.0 * unit(rng)) * kDegree, aspect = 0.5 + 1.5 * unit(rng);
            const Frustum f(eye, forward, {0.0, 0.0, 1.0}, fovY, aspect, 0.3, 100.0 + 500.0 * unit(rng));
            const auto cells = grid.cellsInFrustum(f, zMin, zMax);
            ASSERT_TRUE(std::is_sorted(cells.begin(), cells.end()));
            const std::set<HexCoord> found(cells.begin(), cells.end());

            // Random points inside the frustum and the slab must land in listed cells.
            const auto c = f.corners();
            for (int s = 0; s < 3000; ++s) {
                const double a = unit(rng), b = unit(rng), t = unit(rng);
                const glm::dvec3 nearPoint = glm::mix(glm::mix(c[0], c[1], a), glm::mix(c[3], c[2], a), b);
                const glm::dvec3 farPoint = glm::mix(glm::mix(c[4], c[5], a), glm::mix(c[7], c[6], a), b);
                const glm::dvec3 p = glm::mix(nearPoint, farPoint, t);
                if (p.z < zMin || p.z > zMax) continue;
                ASSERT_TRUE(found.count(grid.cellOf({p.x, p.y}))) << "camera " << i;
            }
            // Every cell with a sampled prism point inside the frustum is listed.
            for (HexCoord cell : spiral(grid.cellOf({eye.x, eye.y}), 16)) {
                const glm::dvec2 centre = grid.center(cell);
                for (int s = 0; s < 40; ++s) {
                    const glm::dvec2 p = centre + glm::dvec2(unit(rng) - 0.5, unit(rng) - 0.5) * 69.0;
                    if (grid.cellOf(p) != cell) continue;
                    if (f.contains({p.x, p.y, zMin + (zMax - zMin) * unit(rng)})) {
                        ASSERT_TRUE(found.count(cell)) << "camera " << i;
                        break;
                    }
                }
            }
        }
    }
}

template <typename F> void expectInvalidNaming(F f, const std::string& name) {
    try {
        f();
        ADD_FAILURE() << "no exception; expected one naming " << name;
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
}

TEST(Frustum, InvalidCamerasNameTheArgument) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const glm::dvec3 eye(0.0), fwd(1.0, 0.0, 0.0), up(0.0, 0.0, 1.0);
    const double fov = 1.0;
    expectInvalidNaming([&] { Frustum({nan, 0.0, 0.0}, fwd, up, fov, 1.0, 1.0, 2.0); }, "position");
    expectInvalidNaming([&] { Frustum(eye, glm::dvec3(0.0), up, fov, 1.0, 1.0, 2.0); }, "forward");
    expectInvalidNaming([&] { Frustum(eye, fwd, {2.0, 0.0, 0.0}, fov, 1.0, 1.0, 2.0); }, "up");
    expectInvalidNaming([&] { Frustum(eye, fwd, up, 0.0, 1.0, 1.0, 2.0); }, "fovY");
    expectInvalidNaming([&] { Frustum(eye, fwd, up, std::numbers::pi, 1.0, 1.0, 2.0); }, "fovY");
    expectInvalidNaming([&] { Frustum(eye, fwd, up, fov, -1.0, 1.0, 2.0); }, "aspect");
    expectInvalidNaming([&] { Frustum(eye, fwd, up, fov, 1.0, 0.0, 2.0); }, "near");
    expectInvalidNaming([&] { Frustum(eye, fwd, up, fov, 1.0, 1.0, 1.0); }, "far");
    expectInvalidNaming([&] { Frustum(eye, fwd, up, fov, 1.0, 1.0, nan); }, "far");

    const HexGrid grid(10.0);
    const Frustum f(eye, fwd, up, fov, 1.0, 1.0, 2.0);
    expectInvalidNaming([&] { grid.cellsInFrustum(f, nan, 1.0); }, "zMin");
    expectInvalidNaming([&] { grid.cellsInFrustum(f, 0.0, INFINITY); }, "zMax");
    expectInvalidNaming([&] { grid.cellsInFrustum(f, 2.0, 1.0); }, "zMin");
    // A far plane 1e6 km away over small cells is refused, not allocated.
    const Frustum vast({0.0, 0.0, 5.0}, {1.0, 0.0, -0.001}, up, 1.5, 2.0, 1.0, 1e9);
    EXPECT_THROW(grid.cellsInFrustum(vast, 0.0, 10.0), std::length_error);
}

} // namespace
} // namespace hexlod::cells
