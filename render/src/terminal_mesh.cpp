// Terminal mesh helpers: colour packing, bounds and content hash, and the normal transform
// of the unit-scope-space contract (terminal_mesh.h).
#include "hexlod/render/terminal_mesh.h"

#include "hexlod/grammar/position_hash.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace hexlod::render {
namespace {

uint32_t channel(float v) {
    if (!(v > 0.0f)) return 0; // NaN too
    return static_cast<uint32_t>(std::lround(std::min(v, 1.0f) * 255.0f));
}

// Eight bytes per step, one multiply each (a rotate-xor-multiply chain), then the splitmix
// finaliser for avalanche; the tail is zero-padded and the byte count is mixed in, so meshes
// that differ only by trailing zeros still differ.
uint64_t hashBytes(uint64_t key, const void* data, size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    uint64_t h = key ^ (size * 0x9e3779b97f4a7c15ull);
    size_t i = 0;
    for (; i + 8 <= size; i += 8) {
        uint64_t word;
        std::memcpy(&word, bytes + i, 8);
        h = ((h ^ word) << 29 | (h ^ word) >> 35) * 0xff51afd7ed558ccdull;
    }
    if (i < size) {
        uint64_t word = 0;
        std::memcpy(&word, bytes + i, size - i);
        h = ((h ^ word) << 29 | (h ^ word) >> 35) * 0xff51afd7ed558ccdull;
    }
    return grammar::mixBits(h);
}

// Ratio used for an axis whose nominal or scope size is 0: a flat nominal axis carries no
// normal component to rescale, and a flattened scope axis makes the normal point along it.
constexpr float kFlattened = 1e12f;

glm::vec3 normalizedOr(const glm::vec3& v, const glm::vec3& fallback) {
    const float length = glm::length(v);
    return length > 0.0f && std::isfinite(length) ? v / length : fallback;
}

} // namespace

uint32_t packRgba(float r, float g, float b, float a) {
    return channel(r) | channel(g) << 8 | channel(b) << 16 | channel(a) << 24;
}

glm::vec4 unpackRgba(uint32_t rgba) {
    return glm::vec4(float(rgba & 0xffu), float((rgba >> 8) & 0xffu), float((rgba >> 16) & 0xffu),
                     float(rgba >> 24)) /
           255.0f;
}

void vertexBounds(std::span<const MeshVertex> vertices, glm::vec3& lo, glm::vec3& hi) {
    lo = glm::vec3(std::numeric_limits<float>::max());
    hi = glm::vec3(std::numeric_limits<float>::lowest());
    for (const MeshVertex& v : vertices) {
        lo = glm::min(lo, v.position);
        hi = glm::max(hi, v.position);
    }
}

void finalizeMesh(TerminalMesh& mesh) {
    vertexBounds(mesh.vertices, mesh.boundsMin, mesh.boundsMax);
    if (mesh.vertices.empty()) mesh.boundsMin = mesh.boundsMax = glm::vec3(0.0f);
    const uint64_t h =
        hashBytes(0x6d657368ull, mesh.vertices.data(), mesh.vertices.size() * sizeof(MeshVertex));
    mesh.contentHash = hashBytes(h, mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t));
}

glm::vec3 nominalShapeSize(float width, float height, float depthRatio) {
    return {width, height, depthRatio * std::min(width, height)};
}

glm::vec3 scopeNormal(const glm::vec3& n, const glm::vec3& nominal, const glm::vec3& scope) {
    glm::vec3 ratio;
    for (int i = 0; i < 3; ++i) {
        if (nominal[i] <= 0.0f)
            ratio[i] = 1.0f;
        else if (scope[i] <= 0.0f)
            ratio[i] = kFlattened;
        else
            ratio[i] = nominal[i] / scope[i];
    }
    return normalizedOr(ratio * n, glm::vec3(0, 0, 1));
}

glm::vec3 unitSpaceNormal(const glm::vec3& n, const glm::vec3& nominal) {
    const glm::vec3 scale(nominal.x > 0.0f ? nominal.x : 1.0f, nominal.y > 0.0f ? nominal.y : 1.0f,
                          nominal.z > 0.0f ? nominal.z : 1.0f);
    return normalizedOr(scale * n, glm::vec3(0, 0, 1));
}

} // namespace hexlod::render
