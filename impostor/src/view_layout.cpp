// Octahedral and hemi-octahedral view grids.
#include "hexlod/impostor/view_layout.h"

#include <cmath>

namespace hexlod::impostor {

glm::vec2 encodeOctahedral(const glm::vec3& d) {
    float l1 = std::abs(d.x) + std::abs(d.y) + std::abs(d.z);
    glm::vec2 p(d.x / l1, d.y / l1);
    if (d.z < 0.0f) {
        glm::vec2 folded(1.0f - std::abs(p.y), 1.0f - std::abs(p.x));
        p = glm::vec2(p.x >= 0.0f ? folded.x : -folded.x, p.y >= 0.0f ? folded.y : -folded.y);
    }
    return p;
}

glm::vec3 decodeOctahedral(const glm::vec2& p) {
    glm::vec3 d(p.x, p.y, 1.0f - std::abs(p.x) - std::abs(p.y));
    if (d.z < 0.0f) {
        glm::vec2 folded(1.0f - std::abs(p.y), 1.0f - std::abs(p.x));
        d.x = p.x >= 0.0f ? folded.x : -folded.x;
        d.y = p.y >= 0.0f ? folded.y : -folded.y;
    }
    return glm::normalize(d);
}

glm::vec2 encodeHemiOctahedral(const glm::vec3& d) {
    float l1 = std::abs(d.x) + std::abs(d.y) + std::abs(d.z);
    float x = d.x / l1, y = d.y / l1;
    return glm::vec2(x + y, x - y);
}

glm::vec3 decodeHemiOctahedral(const glm::vec2& p) {
    float x = 0.5f * (p.x + p.y), y = 0.5f * (p.x - p.y);
    return glm::normalize(glm::vec3(x, y, std::max(0.0f, 1.0f - std::abs(x) - std::abs(y))));
}

ViewBasis viewBasis(ViewSphere sphere, const glm::vec3& forward) {
    glm::vec3 primary = sphere == ViewSphere::Hemisphere ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
    glm::vec3 secondary = sphere == ViewSphere::Hemisphere ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    glm::vec3 reference = std::abs(glm::dot(forward, primary)) > 0.999f ? secondary : primary;
    glm::vec3 right = glm::normalize(glm::cross(reference, forward));
    return {right, glm::cross(forward, right), forward};
}

glm::vec3 ViewLayout::direction(uint32_t index) const {
    float column = float(index % grid), row = float(index / grid);
    if (sphere == ViewSphere::Hemisphere) {
        float scale = 2.0f / float(grid - 1);
        return decodeHemiOctahedral(glm::vec2(column * scale - 1.0f, row * scale - 1.0f));
    }
    float scale = 2.0f / float(grid);
    return decodeOctahedral(glm::vec2((column + 0.5f) * scale - 1.0f, (row + 0.5f) * scale - 1.0f));
}

glm::uvec2 ViewLayout::tileOrigin(uint32_t index) const {
    return glm::uvec2((index % grid) * viewResolution, (index / grid) * viewResolution);
}

bool ViewLayout::validate(std::string& error) const {
    if (grid < kMinGrid || grid > kMaxGrid) {
        error = "view grid " + std::to_string(grid) + " is outside [" + std::to_string(kMinGrid) + ", " +
                std::to_string(kMaxGrid) + "]";
        return false;
    }
    if (viewResolution > kMaxViewResolution) {
        error = "view resolution " + std::to_string(viewResolution) + " exceeds " +
                std::to_string(kMaxViewResolution);
        return false;
    }
    if (viewResolution < 4 || 2 * padding >= viewResolution) {
        error = "view resolution " + std::to_string(viewResolution) + " with padding " +
                std::to_string(padding) + " leaves no inner area";
        return false;
    }
    if (uint64_t(grid) * viewResolution > kMaxAtlasSize) {
        error = "atlas of " + std::to_string(uint64_t(grid) * viewResolution) + " texels exceeds " +
                std::to_string(kMaxAtlasSize);
        return false;
    }
    return true;
}

} // namespace hexlod::impostor
