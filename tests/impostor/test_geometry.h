// Small hand-built geometry for impostor tests: a window of boxes (frame, recessed glass, a
// protruding sill) in metric shape space, so the bake sees depth, colour and parallax.
#pragma once

#include "hexlod/impostor/impostor_baker.h"

namespace hexlod::impostor::testing {

inline uint32_t rgba(float r, float g, float b) {
    auto byte = [](float v) { return uint32_t(v * 255.0f + 0.5f); };
    return byte(r) | byte(g) << 8 | byte(b) << 16 | 255u << 24;
}

// An axis-aligned box with outward normals, counter-clockwise faces.
inline void addBox(BakeGeometry& g, glm::vec3 lo, glm::vec3 hi, uint32_t colour) {
    const glm::vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const glm::vec3& n : normals) {
        // Two axes spanning the face, ordered so (u x v) = n.
        glm::vec3 u = std::abs(n.x) > 0 ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
        glm::vec3 v = glm::cross(n, u);
        glm::vec3 centre = 0.5f * (lo + hi) + 0.5f * n * (hi - lo);
        glm::vec3 half = 0.5f * (hi - lo);
        uint32_t base = uint32_t(g.vertices.size());
        for (glm::vec2 c : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
            glm::vec3 p = centre + c.x * u * half + c.y * v * half;
            g.vertices.push_back({p, n, glm::vec2(0), colour});
        }
        for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) g.indices.push_back(base + i);
    }
}

inline BakeGeometry testWindow() {
    BakeGeometry g;
    const uint32_t frame = rgba(0.9f, 0.9f, 0.85f), glass = rgba(0.15f, 0.25f, 0.35f),
                   sill = rgba(0.6f, 0.55f, 0.5f);
    addBox(g, {0.0f, 0.0f, 0.0f}, {1.2f, 0.1f, 0.12f}, frame);    // bottom rail
    addBox(g, {0.0f, 1.4f, 0.0f}, {1.2f, 1.5f, 0.12f}, frame);    // top rail
    addBox(g, {0.0f, 0.1f, 0.0f}, {0.1f, 1.4f, 0.12f}, frame);    // left stile
    addBox(g, {1.1f, 0.1f, 0.0f}, {1.2f, 1.4f, 0.12f}, frame);    // right stile
    addBox(g, {0.1f, 0.1f, -0.1f}, {1.1f, 1.4f, -0.08f}, glass);  // recessed pane
    addBox(g, {-0.05f, -0.08f, 0.0f}, {1.25f, 0.0f, 0.3f}, sill); // protruding sill
    g.hash = 42;
    return g;
}

} // namespace hexlod::impostor::testing
