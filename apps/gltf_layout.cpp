#include "gltf_layout.h"

namespace hexlod::apps {
namespace {

using nlohmann::json;
using render::MeshVertex;

void writeU32(std::ostream& out, uint32_t v) {
    const char bytes[4] = {char(v & 0xff), char((v >> 8) & 0xff), char((v >> 16) & 0xff), char(v >> 24)};
    out.write(bytes, 4);
}

} // namespace

size_t GltfLayout::addView(uint64_t offset, uint64_t length, uint32_t stride, int target) {
    json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}};
    if (stride) view["byteStride"] = stride;
    if (target) view["target"] = target;
    views_.push_back(view);
    return views_.size() - 1;
}

size_t GltfLayout::addAccessor(size_t view, uint64_t offset, int componentType, uint64_t count,
                               const char* type, bool normalized) {
    json a = {{"bufferView", view},
              {"byteOffset", offset},
              {"componentType", componentType},
              {"count", count},
              {"type", type}};
    if (normalized) a["normalized"] = true;
    accessors_.push_back(a);
    return accessors_.size() - 1;
}

json GltfLayout::describePrimitive(uint64_t vertexAt, uint64_t vertexCount, uint64_t indexAt,
                                   uint64_t indexCount, const glm::vec3& lo, const glm::vec3& hi) {
    const size_t vertexView =
        addView(vertexAt, vertexCount * sizeof(MeshVertex), sizeof(MeshVertex), kGltfArrayBuffer);
    const size_t indexView = addView(indexAt, indexCount * 4, 0, kGltfElementArrayBuffer);
    const size_t position =
        addAccessor(vertexView, offsetof(MeshVertex, position), kGltfFloat, vertexCount, "VEC3");
    accessors_[position]["min"] = {lo.x, lo.y, lo.z};
    accessors_[position]["max"] = {hi.x, hi.y, hi.z};
    json primitive;
    primitive["attributes"] = {
        {"POSITION", position},
        {"NORMAL", addAccessor(vertexView, offsetof(MeshVertex, normal), kGltfFloat, vertexCount, "VEC3")},
        {"TEXCOORD_0", addAccessor(vertexView, offsetof(MeshVertex, uv), kGltfFloat, vertexCount, "VEC2")},
        {"COLOR_0",
         addAccessor(vertexView, offsetof(MeshVertex, rgba), kGltfUnsignedByte, vertexCount, "VEC4", true)}};
    primitive["indices"] = addAccessor(indexView, 0, kGltfUnsignedInt, indexCount, "SCALAR");
    primitive["material"] = 0;
    return primitive;
}

json vertexColourMaterial() {
    return {{"name", "vertex colour"},
            {"pbrMetallicRoughness",
             {{"baseColorFactor", {1, 1, 1, 1}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.9}}}};
}

uint64_t writeGlbPrologue(std::ostream& out, const std::string& json, uint64_t binBytes) {
    const uint64_t jsonBytes = gltfPadded(json.size()), binPadded = gltfPadded(binBytes);
    const uint64_t total = 12 + 8 + jsonBytes + (binBytes ? 8 + binPadded : 0);
    out.write("glTF", 4);
    writeU32(out, 2);
    writeU32(out, uint32_t(total));
    writeU32(out, uint32_t(jsonBytes));
    writeU32(out, 0x4E4F534A); // "JSON"
    out << json << std::string(jsonBytes - json.size(), ' ');
    if (binBytes) {
        writeU32(out, uint32_t(binPadded));
        writeU32(out, 0x004E4942); // "BIN\0"
    }
    return total;
}

} // namespace hexlod::apps
