// Geometry primitives the shape generators are written with. Generators work in *metric
// nominal space*: metres at the shape's declared size, x in [0, W], y in [0, H] and depth z in
// [-D, D] out of the wall plane; finish() divides by (W, H, D) into unit scope space and keeps
// the metric normals (terminal_mesh.h). Every primitive orients its faces from an outward
// direction it knows rather than from vertex order, so no generator can get a winding wrong.
#pragma once

#include "hexlod/render/terminal_mesh.h"

#include <glm/glm.hpp>

#include <functional>
#include <span>
#include <string>
#include <vector>

namespace hexlod::render {

// Linear RGBA8 from 0..255 components, R in the low byte.
constexpr uint32_t rgba8(uint32_t r, uint32_t g, uint32_t b, uint32_t a = 255) {
    return r | g << 8 | b << 16 | a << 24;
}

// Materials, in linear RGB.
namespace palette {
inline constexpr uint32_t kGlass = rgba8(14, 22, 30);
inline constexpr uint32_t kWhiteFrame = rgba8(190, 190, 182);
inline constexpr uint32_t kBrownWood = rgba8(52, 24, 10);
inline constexpr uint32_t kGreenWood = rgba8(14, 46, 24);
inline constexpr uint32_t kStone = rgba8(128, 118, 102);
inline constexpr uint32_t kLightStone = rgba8(168, 158, 138);
inline constexpr uint32_t kPlaster = rgba8(150, 124, 96);
inline constexpr uint32_t kTerracotta = rgba8(112, 32, 14);
inline constexpr uint32_t kBrick = rgba8(92, 30, 18);
inline constexpr uint32_t kDarkMetal = rgba8(18, 18, 20);
inline constexpr uint32_t kSteel = rgba8(92, 96, 102);
inline constexpr uint32_t kAluminium = rgba8(140, 144, 150);
inline constexpr uint32_t kConcrete = rgba8(104, 102, 98);
inline constexpr uint32_t kWoodDeck = rgba8(80, 50, 26);
inline constexpr uint32_t kSoil = rgba8(30, 18, 10);
inline constexpr uint32_t kLeaf = rgba8(16, 52, 8);
inline constexpr uint32_t kLeafBack = rgba8(30, 70, 16);
inline constexpr uint32_t kBark = rgba8(34, 20, 11);
inline constexpr uint32_t kFruit = rgba8(130, 12, 6);
inline constexpr uint32_t kFabricRed = rgba8(120, 14, 12);
inline constexpr uint32_t kFabricWhite = rgba8(200, 196, 186);
inline constexpr uint32_t kFlowerRed = rgba8(180, 10, 20);
inline constexpr uint32_t kFlowerYellow = rgba8(200, 150, 10);
inline constexpr uint32_t kFallback = rgba8(230, 0, 200);
} // namespace palette

// Bit mask of box faces.
enum BoxFace : uint32_t {
    kNegX = 1,
    kPosX = 2,
    kNegY = 4,
    kPosY = 8,
    kNegZ = 16, // the back, against the wall
    kPosZ = 32,
    kAllFaces = 63,
    kNoBack = kAllFaces & ~kNegZ,
};

class MeshBuilder {
public:
    explicit MeshBuilder(const glm::vec3& nominalSize) : size_(nominalSize) {
        vertices_.reserve(512);
        indices_.reserve(1536);
    }

    float W() const { return size_.x; }
    float H() const { return size_.y; }
    float D() const { return size_.z; }
    size_t triangleCount() const { return indices_.size() / 3; }

    // A flat triangle or convex polygon; its front faces `outward`.
    void polygon(std::span<const glm::vec3> points, const glm::vec3& outward, uint32_t rgba);
    void quad(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d,
              const glm::vec3& outward, uint32_t rgba);
    // Front and back face of a thin sheet (leaves, glass seen from both sides).
    void twoSidedQuad(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d,
                      const glm::vec3& front, uint32_t frontRgba, uint32_t backRgba);

    // Axis-aligned box; `faces` picks the sides (hidden ones against the wall can be left out).
    void box(const glm::vec3& lo, const glm::vec3& hi, uint32_t rgba, uint32_t faces = kAllFaces);

    // A closed polygon in the plane (pu, pv), swept along `axis` from s0 to s1: its sides face
    // away from the polygon (or into it with `inward`), its caps, if asked for, face -axis at s0
    // and +axis at s1. `end` (same vertex count, or empty for the same polygon) is the profile
    // at s1, for tapering lofts. With `openLast` the side from the last point back to the first
    // is left out (the edge lying on the wall).
    struct Sweep {
        std::span<const glm::vec2> profile{};
        std::span<const glm::vec2> end{};
        glm::vec3 pu{1, 0, 0}, pv{0, 1, 0}, axis{0, 0, 1};
        float s0 = 0.0f, s1 = 1.0f;
        bool caps = true;
        bool inward = false;
        bool openLast = false;
    };
    void sweep(const Sweep& sweep, uint32_t rgba);

    // Frame around an opening in the xy plane: the strip between the closed outlines `outer`
    // and `inner` (same vertex count, both counter-clockwise) at z1, the outer wall and the
    // inner reveal from z0 to z1, and the back strip at z0 if asked for.
    void ring(std::span<const glm::vec2> outer, std::span<const glm::vec2> inner, float z0, float z1,
              uint32_t rgba, bool back = false);

    // Smooth cone frustum from a (radius ra) to b (radius rb) with `segments` around and
    // `rings` along; `radiusScale(ring, segment)` perturbs the radius (bark), caps are flat.
    void frustum(const glm::vec3& a, const glm::vec3& b, float ra, float rb, int segments, int rings,
                 uint32_t rgba, bool capA, bool capB,
                 const std::function<float(int, int)>& radiusScale = nullptr);
    // UV sphere (ellipsoid in metric space) with smooth normals: 2 × slices × (stacks - 1) triangles.
    void sphere(const glm::vec3& centre, const glm::vec3& radii, int slices, int stacks, uint32_t rgba);
    // Grid over [x0, x1] × [y0, y1] at depth z(x, y), normals from central differences.
    void heightField(float x0, float x1, float y0, float y1, int nx, int ny,
                     const std::function<float(float, float)>& z, uint32_t rgba);

    // Unit scope space, bounds and hash; names the shape.
    // Vertices so far, e.g. to tag the ones a call adds.
    size_t vertexCount() const { return vertices_.size(); }
    TerminalMesh finish(const std::string& shape, const std::string& source) const;

private:
    uint32_t vertex(const glm::vec3& p, const glm::vec3& n, uint32_t rgba);
    // Emits (a, b, c) turned so that its geometric normal agrees with `outward`.
    void orientedTriangle(uint32_t a, uint32_t b, uint32_t c, const glm::vec3& outward);

    glm::vec3 size_;
    std::vector<MeshVertex> vertices_;
    std::vector<uint32_t> indices_;
};

// A polyline of straight runs and circular arcs, for moulding and fin profiles.
struct Profile {
    std::vector<glm::vec2> points;
    Profile& to(float x, float y) {
        points.push_back({x, y});
        return *this;
    }
    // The elliptic arc centre + radii ⊙ (cos a, sin a) from angle a0 to a1 (degrees), without its
    // start point.
    Profile& arc(glm::vec2 centre, glm::vec2 radii, float a0, float a1, int segments);
};

// Closed outlines in the xy plane, counter-clockwise.
std::vector<glm::vec2> rectangleOutline(float x0, float y0, float x1, float y1);
// A rectangle with a semicircular (or segmental, for a rise below half the width) head of
// `arcSegments` pieces, starting at the bottom left.
std::vector<glm::vec2> archOutline(float x0, float y0, float x1, float y1, float rise, int arcSegments);

} // namespace hexlod::render
