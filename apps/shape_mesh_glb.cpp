#include "shape_mesh_glb.h"

#include "gltf_layout.h"

#include "hexlod/cache/batch_key.h"

#include <limits>
#include <sstream>

namespace hexlod::apps {

std::vector<uint8_t> shapeMeshGlb(const render::TerminalMesh& mesh, const std::string& name) {
    std::vector<render::MeshVertex> vertices = mesh.vertices;
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    for (render::MeshVertex& v : vertices) {
        v.normal = render::unitSpaceNormal(v.normal, mesh.nominalSize);
        lo = glm::min(lo, v.position), hi = glm::max(hi, v.position);
    }
    if (vertices.empty()) lo = hi = glm::vec3(0.0f);
    const uint64_t vertexBytes = vertices.size() * sizeof(render::MeshVertex);
    const uint64_t indexBytes = mesh.indices.size() * sizeof(uint32_t);
    GltfLayout layout;
    nlohmann::json primitives = nlohmann::json::array();
    if (!mesh.indices.empty())
        primitives.push_back(
            layout.describePrimitive(0, vertices.size(), vertexBytes, mesh.indices.size(), lo, hi));
    const glm::vec3 n = mesh.nominalSize;
    nlohmann::json document = {
        {"asset",
         {{"version", "2.0"},
          {"generator", "hexlod 0.1.0"},
          {"extras",
           {{"hexlod",
             {{"space", "unit scope space: x along the facade, y up it, z out of it; scale by (w, h, d)"},
              {"nominal_size", {n.x, n.y, n.z}},
              {"content_hash", cache::hexDigest(mesh.contentHash)},
              {"source", mesh.source}}}}}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"name", name}, {"mesh", 0}}}},
        {"meshes", {{{"name", name}, {"primitives", primitives}}}},
        {"materials", {vertexColourMaterial()}},
        {"buffers", {{{"byteLength", vertexBytes + indexBytes}}}},
    };
    // glTF needs at least one primitive per mesh; an empty shape gets none of the arrays.
    if (!primitives.empty()) {
        document["accessors"] = layout.accessors();
        document["bufferViews"] = layout.views();
    } else {
        document.erase("meshes");
        document["nodes"][0].erase("mesh");
        document.erase("buffers");
    }
    std::ostringstream out;
    const uint64_t binBytes = primitives.empty() ? 0 : vertexBytes + indexBytes;
    writeGlbPrologue(out, document.dump(), binBytes);
    if (binBytes) {
        out.write(reinterpret_cast<const char*>(vertices.data()), std::streamsize(vertexBytes));
        out.write(reinterpret_cast<const char*>(mesh.indices.data()), std::streamsize(indexBytes));
        out << std::string(gltfPadded(binBytes) - binBytes, '\0');
    }
    const std::string bytes = out.str();
    return {bytes.begin(), bytes.end()};
}

} // namespace hexlod::apps
