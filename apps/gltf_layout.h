// The JSON side of glTF buffer data (glTF 2.0 §3.6): buffer views, accessors and the triangle
// primitive over interleaved render::MeshVertex data, shared by the city export and the
// per-shape meshes the service hands out, so both describe a vertex the same way.
#pragma once

#include "hexlod/render/terminal_mesh.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <ostream>
#include <string>

namespace hexlod::apps {

inline constexpr int kGltfFloat = 5126, kGltfUnsignedByte = 5121, kGltfUnsignedInt = 5125;
inline constexpr int kGltfArrayBuffer = 34962, kGltfElementArrayBuffer = 34963;

class GltfLayout {
public:
    // Both return the new entry's index. `stride` 0 and `target` 0 are left out.
    size_t addView(uint64_t offset, uint64_t length, uint32_t stride, int target);
    size_t addAccessor(size_t view, uint64_t offset, int componentType, uint64_t count, const char* type,
                       bool normalized = false);
    // A triangle primitive over MeshVertex vertices and 32-bit indices already in buffer 0:
    // POSITION (with its bounds lo, hi), NORMAL, TEXCOORD_0 and normalised COLOR_0 over one
    // interleaved view, and material 0 (vertexColourMaterial()).
    nlohmann::json describePrimitive(uint64_t vertexAt, uint64_t vertexCount, uint64_t indexAt,
                                     uint64_t indexCount, const glm::vec3& lo, const glm::vec3& hi);

    const nlohmann::json& views() const { return views_; }
    const nlohmann::json& accessors() const { return accessors_; }

private:
    nlohmann::json views_ = nlohmann::json::array(), accessors_ = nlohmann::json::array();
};

// The one material every hexlod mesh uses: white base colour times the vertex colour, rough
// and not metallic.
nlohmann::json vertexColourMaterial();

// Bytes to the next multiple of 4, as glb chunks and buffer views align.
inline uint64_t gltfPadded(uint64_t n) {
    return (n + 3) & ~uint64_t(3);
}
// The .glb container up to the BIN chunk's data (glTF 2.0 §4.4): header, JSON chunk padded
// with spaces and, when `binBytes` > 0, the BIN chunk's header. The caller then writes
// gltfPadded(binBytes) bytes of buffer. Returns the whole file's length.
uint64_t writeGlbPrologue(std::ostream& out, const std::string& json, uint64_t binBytes);

} // namespace hexlod::apps
