#include "city_gltf_export.h"

#include "gltf_binary_stream.h"
#include "gltf_layout.h"

#include "hexlod/render/base_volume_mesh.h"

#include <nlohmann/json.hpp>

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <limits>
#include <set>
#include <unordered_map>

namespace hexlod::apps {
namespace {

using nlohmann::json;
using render::MeshVertex;
using render::TerminalMesh;

constexpr const char* kInstancing = "EXT_mesh_gpu_instancing";
// Scale floor for a flattened scope axis, so instance matrices stay invertible (metres; far
// below a millimetre of position).
constexpr float kMinScale = 1e-4f;
// Instances baked per block in --flatten, bounding the memory of one block.
constexpr size_t kBakeBlock = 4096;

std::string cellName(cells::HexCoord c) {
    return std::to_string(c.q) + "," + std::to_string(c.r);
}

// One terminal as the export needs it: scope origin, rotation and size, cell-relative.
struct Instance {
    glm::vec3 translation;
    glm::dquat rotation;
    glm::vec3 scope; // (w, h, d), d exact
};

Instance instanceOf(const grammar::TerminalRecord& record) {
    const grammar::Terminal t = grammar::unpackTerminal(record);
    const glm::dquat q = glm::normalize(glm::dquat(t.orientation));
    const float d = t.depthRatio * std::min(t.size.x, t.size.y);
    return {t.position, q, glm::vec3(t.size, d)};
}

class Exporter {
public:
    Exporter(const cells::BatchCatalog& catalog, const render::TerminalMeshLibrary& library,
             const CityExportOptions& options, uint64_t limit)
        : catalog_(catalog), library_(library), options_(options), stream_(options.output, limit) {}

    CityExportReport run(const std::vector<cells::HexCoord>& chosen) {
        report_.origin = catalog_.cellOrigin(chosen.front());
        json cellNodes = json::array();
        nodes_.push_back({{"name", "hexlod city (z up)"},
                          {"rotation", {-0.70710678118654752, 0.0, 0.0, 0.70710678118654752}}});
        for (const cells::HexCoord cell : chosen) {
            if (!exportCell(cell)) return fail(stream_.error());
            cellNodes.push_back(nodes_.size() - 1);
        }
        nodes_[0]["children"] = cellNodes;
        return finish();
    }

private:
    CityExportReport fail(const std::string& error) {
        report_.error = error;
        return report_;
    }

    static void grow(glm::vec3& lo, glm::vec3& hi, const std::vector<MeshVertex>& vertices) {
        for (const MeshVertex& v : vertices) lo = glm::min(lo, v.position), hi = glm::max(hi, v.position);
    }

    json writePrimitive(const std::vector<MeshVertex>& vertices, const std::vector<uint32_t>& indices) {
        if (!stream_.reserve(vertices.size() * sizeof(MeshVertex) + indices.size() * 4 + 4))
            return json::object();
        glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
        grow(lo, hi, vertices);
        const uint64_t vertexAt = stream_.append(vertices.data(), vertices.size() * sizeof(MeshVertex));
        const uint64_t indexAt = stream_.append(indices.data(), indices.size() * 4);
        return layout_.describePrimitive(vertexAt, vertices.size(), indexAt, indices.size(), lo, hi);
    }

    // The terminal mesh as a glTF mesh, written on first use: normals turned into those of the
    // unit-space mesh, which glTF's node-scale rule carries to each stretched instance.
    size_t terminalMesh(const TerminalMesh& mesh, const std::string& name) {
        const auto found = meshIndex_.find(&mesh);
        if (found != meshIndex_.end()) return found->second;
        std::vector<MeshVertex> vertices = mesh.vertices;
        for (MeshVertex& v : vertices) v.normal = render::unitSpaceNormal(v.normal, mesh.nominalSize);
        meshes_.push_back(
            {{"name", name}, {"primitives", json::array({writePrimitive(vertices, mesh.indices)})}});
        return meshIndex_[&mesh] = meshes_.size() - 1;
    }

    // Every instance of `mesh` in the cell baked into one primitive, streamed block by block:
    // 36-byte vertices keep the blocks contiguous in the buffer, so one view spans them.
    json bakedPrimitive(const TerminalMesh& mesh, const std::vector<Instance>& instances) {
        const uint64_t vertexCount = instances.size() * mesh.vertices.size();
        const uint64_t indexCount = instances.size() * mesh.indices.size();
        if (vertexCount > std::numeric_limits<uint32_t>::max()) {
            stream_.refuse("one cell bakes more than 2^32 vertices of " + mesh.shape +
                           "; export it without --flatten");
            return json::object();
        }
        if (!stream_.reserve(vertexCount * sizeof(MeshVertex) + indexCount * 4 + 4)) return json::object();
        glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
        std::vector<MeshVertex> vertices;
        uint64_t vertexAt = 0;
        for (size_t first = 0; first < instances.size(); first += kBakeBlock) {
            vertices.clear();
            for (size_t i = first; i < std::min(instances.size(), first + kBakeBlock); ++i) {
                const Instance& in = instances[i];
                const glm::mat3 r = glm::mat3_cast(glm::quat(in.rotation));
                for (const MeshVertex& v : mesh.vertices) {
                    MeshVertex out = v;
                    out.position = in.translation + r * (v.position * in.scope);
                    out.normal =
                        glm::normalize(r * render::scopeNormal(v.normal, mesh.nominalSize, in.scope));
                    vertices.push_back(out);
                }
            }
            grow(lo, hi, vertices);
            const uint64_t at = stream_.append(vertices.data(), vertices.size() * sizeof(MeshVertex));
            if (first == 0) vertexAt = at;
        }
        std::vector<uint32_t> indices;
        uint64_t indexAt = 0;
        for (size_t first = 0; first < instances.size(); first += kBakeBlock) {
            indices.clear();
            for (size_t i = first; i < std::min(instances.size(), first + kBakeBlock); ++i) {
                const uint32_t base = static_cast<uint32_t>(i * mesh.vertices.size());
                for (const uint32_t index : mesh.indices) indices.push_back(base + index);
            }
            const uint64_t at = stream_.append(indices.data(), indices.size() * 4);
            if (first == 0) indexAt = at;
        }
        return layout_.describePrimitive(vertexAt, vertexCount, indexAt, indexCount, lo, hi);
    }

    void instancingNode(json& children, const TerminalMesh& mesh, const std::string& name,
                        const std::vector<Instance>& instances) {
        const size_t meshIndex = terminalMesh(mesh, name);
        const size_t n = instances.size();
        std::vector<float> data(n * 10);
        for (size_t i = 0; i < n; ++i) {
            const Instance& in = instances[i];
            std::copy_n(&in.translation.x, 3, &data[3 * i]);
            const glm::quat q(in.rotation);
            data[3 * n + 4 * i] = q.x, data[3 * n + 4 * i + 1] = q.y, data[3 * n + 4 * i + 2] = q.z,
                             data[3 * n + 4 * i + 3] = q.w;
            const glm::vec3 s = glm::max(in.scope, glm::vec3(kMinScale));
            std::copy_n(&s.x, 3, &data[7 * n + 3 * i]);
        }
        const uint64_t at = stream_.append(data.data(), data.size() * sizeof(float));
        const size_t view = layout_.addView(at, data.size() * sizeof(float), 0, 0);
        const json attributes = {{"TRANSLATION", layout_.addAccessor(view, 0, kGltfFloat, n, "VEC3")},
                                 {"ROTATION", layout_.addAccessor(view, 12 * n, kGltfFloat, n, "VEC4")},
                                 {"SCALE", layout_.addAccessor(view, 28 * n, kGltfFloat, n, "VEC3")}};
        nodes_.push_back({{"name", name},
                          {"mesh", meshIndex},
                          {"extensions", {{kInstancing, {{"attributes", attributes}}}}}});
        children.push_back(nodes_.size() - 1);
    }

    bool exportCell(cells::HexCoord cell) {
        // Instances by terminal mesh, in order of first appearance (batch order, then shape).
        std::vector<std::pair<const TerminalMesh*, std::string>> order;
        std::unordered_map<const TerminalMesh*, std::vector<Instance>> instances;
        TerminalMesh base;
        for (const cells::Batch& batch : catalog_.index().batchesOf(cell)) {
            const uint32_t b = static_cast<uint32_t>(&batch - catalog_.index().batches().data());
            const grammar::BatchResult result = catalog_.expand(b);
            ++report_.batches;
            if (result.failed) {
                report_.warnings.push_back("cell " + cellName(cell) + ": batch of grammar " +
                                           catalog_.grammar(batch.grammar).name +
                                           " hit the batch terminal cap and is missing");
            }
            const std::string grammarName =
                std::filesystem::path(catalog_.grammar(batch.grammar).name).stem().string();
            const grammar::TerminalSet& set = result.terminals;
            size_t next = 0;
            for (uint16_t shape = 0; shape < set.countPerShape.size(); ++shape) {
                const uint32_t count = set.countPerShape[shape];
                if (count == 0) continue;
                const TerminalMesh& mesh = library_.mesh(batch.grammar, shape);
                auto& list = instances[&mesh];
                if (list.empty()) order.emplace_back(&mesh, grammarName + "/" + mesh.shape);
                for (uint32_t i = 0; i < count; ++i) list.push_back(instanceOf(set.records[next + i]));
                next += count;
            }
            report_.terminals += set.records.size();
            if (!catalog_.index().isTreeGrammar(batch.grammar)) {
                const TerminalMesh volumes =
                    render::buildBaseVolumes(result.extruded, options_.baseVolumeInset);
                const uint32_t offset = static_cast<uint32_t>(base.vertices.size());
                base.vertices.insert(base.vertices.end(), volumes.vertices.begin(), volumes.vertices.end());
                for (const uint32_t index : volumes.indices) base.indices.push_back(offset + index);
            }
        }
        json children = json::array();
        json flattened = json::array();
        for (const auto& [mesh, name] : order) {
            const std::vector<Instance>& list = instances.at(mesh);
            report_.instances += list.size();
            if (used_.insert(mesh).second) ++report_.terminalMeshes;
            report_.instancesPerMesh[name] += list.size();
            report_.triangles += list.size() * mesh->triangleCount();
            if (options_.flatten)
                flattened.push_back(bakedPrimitive(*mesh, list));
            else
                instancingNode(children, *mesh, name, list);
            if (!stream_.ok()) return false;
        }
        if (!base.indices.empty()) {
            report_.baseVolumeTriangles += base.triangleCount();
            report_.triangles += base.triangleCount();
            const json primitive = writePrimitive(base.vertices, base.indices);
            if (options_.flatten) {
                flattened.push_back(primitive);
            } else {
                meshes_.push_back({{"name", "base volumes " + cellName(cell)}, {"primitives", {primitive}}});
                nodes_.push_back({{"name", "base volumes"}, {"mesh", meshes_.size() - 1}});
                children.push_back(nodes_.size() - 1);
            }
        }
        if (options_.flatten && !flattened.empty()) {
            meshes_.push_back({{"name", "cell " + cellName(cell)}, {"primitives", flattened}});
            nodes_.push_back({{"name", "geometry"}, {"mesh", meshes_.size() - 1}});
            children.push_back(nodes_.size() - 1);
        }
        const glm::dvec3 offset = catalog_.cellOrigin(cell) - report_.origin;
        nodes_.push_back({{"name", "cell " + cellName(cell)},
                          {"translation", {float(offset.x), float(offset.y), float(offset.z)}},
                          {"children", children}});
        ++report_.cells;
        return stream_.ok();
    }

    CityExportReport finish() {
        const std::filesystem::path output(options_.output);
        const bool binary = output.extension() == ".glb";
        const std::string binName = output.stem().string() + ".bin";
        json buffer = {{"byteLength", stream_.size()}};
        if (!binary) buffer["uri"] = binName;
        json document = {
            {"asset",
             {{"version", "2.0"},
              {"generator", "hexlod 0.1.0"},
              {"extras",
               {{"hexlod",
                 {{"origin", {report_.origin.x, report_.origin.y, report_.origin.z}},
                  {"up", "z; the root node turns it to glTF's +y"},
                  {"cells", report_.cells}}}}}}},
            {"scene", 0},
            {"scenes", {{{"nodes", {0}}}}},
            {"nodes", nodes_},
            {"meshes", meshes_},
            {"materials", {vertexColourMaterial()}},
            {"accessors", layout_.accessors()},
            {"bufferViews", layout_.views()},
            {"buffers", {buffer}},
        };
        if (!options_.flatten && report_.terminalMeshes > 0) {
            document["extensionsUsed"] = {kInstancing};
            document["extensionsRequired"] = {kInstancing};
        }
        report_.gltfMeshes = static_cast<uint32_t>(meshes_.size());
        const std::string text = document.dump();
        const std::string binPath = (output.parent_path() / binName).string();
        if (!(binary ? stream_.finishGlb(text) : stream_.finishGltf(text, binPath)))
            return fail(stream_.error());
        std::error_code ec;
        report_.bytes = std::filesystem::file_size(options_.output, ec) +
                        (binary ? 0 : std::filesystem::file_size(binPath, ec));
        report_.ok = true;
        return report_;
    }

    const cells::BatchCatalog& catalog_;
    const render::TerminalMeshLibrary& library_;
    const CityExportOptions& options_;
    GltfBinaryStream stream_;
    CityExportReport report_;
    GltfLayout layout_;
    json nodes_ = json::array(), meshes_ = json::array();
    std::unordered_map<const TerminalMesh*, size_t> meshIndex_;
    std::set<const TerminalMesh*> used_;
};

} // namespace

CityExportReport exportCityGltf(const cells::BatchCatalog& catalog,
                                const render::TerminalMeshLibrary& library,
                                const CityExportOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    CityExportReport failed;
    const std::string extension = std::filesystem::path(options.output).extension().string();
    if (extension != ".glb" && extension != ".gltf") {
        failed.error = options.output + ": a glTF export is written as .glb or .gltf";
        return failed;
    }
    std::vector<cells::HexCoord> chosen;
    std::set<cells::HexCoord> seen;
    if (options.cells.empty()) {
        for (const cells::CellBounds& c : catalog.index().cells()) chosen.push_back(c.cell);
    }
    for (const cells::HexCoord c : options.cells) {
        if (!catalog.index().boundsOf(c)) {
            failed.error = "cell " + cellName(c) + " holds no buildings or trees";
            return failed;
        }
        if (seen.insert(c).second) chosen.push_back(c);
    }
    if (chosen.empty()) {
        failed.error = "the scene has no occupied cell to export";
        return failed;
    }
    if (library.grammarCount() != catalog.index().grammarCount()) {
        failed.error = "the mesh library was built for another scene";
        return failed;
    }
    const uint64_t formatLimit = extension == ".glb"
                                     ? kGlbMaxBytes - (uint64_t(64) << 20) // room for the JSON
                                     : std::numeric_limits<uint64_t>::max();
    const uint64_t limit = options.maxBytes ? std::min(options.maxBytes, formatLimit) : formatLimit;
    Exporter exporter(catalog, library, options, limit);
    CityExportReport report = exporter.run(chosen);
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return report;
}

} // namespace hexlod::apps
