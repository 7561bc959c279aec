// A camera's view frustum for CPU culling of cell bounds: six inward planes and eight corners,
// with conservative box and hexagonal-prism tests in the manner of Inigo Quilez, "Correct
// frustum culling" (https://iquilezles.org/articles/frustumcorrect/): a volume is culled when all
// its corners lie outside one frustum plane, or all frustum corners lie outside one of its faces.
//
// Planes are kept relative to the eye, so distances are computed from small differences and a
// camera 1e7 m from the world origin culls as precisely as one at the origin.
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <vector>

namespace hexlod::cells {

// A point p is inside when dot(normal, p - eye) + offset >= 0; normal has unit length.
struct FrustumPlane {
    glm::dvec3 normal{0.0};
    double offset = 0.0;
};

class Frustum {
public:
    enum PlaneIndex { Left, Right, Bottom, Top, Near, Far };

    // position: the eye (world). forward, up: any length, not parallel (up is re-orthogonalised).
    // fovY: vertical field of view in radians, in (0, pi). aspect: width / height, > 0.
    // 0 < near < far. Throws std::invalid_argument naming the offending argument.
    Frustum(glm::dvec3 position, glm::dvec3 forward, glm::dvec3 up, double fovY, double aspect, double near,
            double far);

    glm::dvec3 eye() const { return eye_; }
    const std::array<FrustumPlane, 6>& planes() const { return planes_; }
    // World corners: near bottom-left, bottom-right, top-right, top-left, then the same on the far
    // plane (left and right as seen by the camera).
    std::array<glm::dvec3, 8> corners() const;

    // All three tests are conservative: false only when the point or volume certainly lies
    // outside. A micrometre of slack keeps rounding from culling what touches the frustum.
    bool contains(glm::dvec3 point) const;
    bool intersectsBox(glm::dvec3 lo, glm::dvec3 hi) const;
    // The pointy-top hexagon of HexGrid (centre, circumradius) extruded over [zMin, zMax].
    bool intersectsPrism(glm::dvec2 center, double circumradius, double zMin, double zMax) const;

    // The ground projection of the frustum clipped to the slab zMin <= z <= zMax: a convex
    // polygon in world x, y, counter-clockwise (may degenerate to a segment or point); empty when
    // the frustum misses the slab.
    std::vector<glm::dvec2> footprint(double zMin, double zMax) const;

private:
    glm::dvec3 eye_;
    std::array<FrustumPlane, 6> planes_;
    std::array<glm::dvec3, 8> cornerOffsets_; // corners relative to the eye
};

} // namespace hexlod::cells
