// glTF 2.0 user shapes through tinygltf (gltf_mesh_loader.h): flatten the node hierarchy, read
// the triangle primitives, fit the result to unit scope space.
#include "hexlod/render/gltf_mesh_loader.h"

#include "gltf_accessors.h"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

namespace hexlod::render {
namespace {

constexpr int kMaxNodeDepth = 64;
constexpr uintmax_t kMaxFileBytes = uintmax_t(1) << 30;

// Geometry gathered in model space before the fit.
struct Gathered {
    std::vector<glm::dvec3> positions, normals;
    std::vector<glm::vec2> uvs;
    std::vector<glm::vec4> colours;
    std::vector<uint32_t> indices;
    size_t skipped = 0;
};

glm::dmat4 localTransform(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) return glm::make_mat4(node.matrix.data());
    glm::dmat4 m(1.0);
    if (node.translation.size() == 3) m = glm::translate(m, glm::make_vec3(node.translation.data()));
    if (node.rotation.size() == 4) {
        const glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
        m *= glm::mat4_cast(glm::normalize(q));
    }
    if (node.scale.size() == 3) m = glm::scale(m, glm::make_vec3(node.scale.data()));
    return m;
}

class Flattener {
public:
    Flattener(const tinygltf::Model& model, Gathered& out) : model_(model), out_(out) {}

    bool mesh(int index, const glm::dmat4& transform) {
        if (index < 0 || size_t(index) >= model_.meshes.size())
            return fail("a node names mesh " + std::to_string(index) + ", which does not exist");
        const glm::dmat3 normalMatrix = glm::inverseTranspose(glm::dmat3(transform));
        const bool mirrored = glm::determinant(glm::dmat3(transform)) < 0.0;
        for (const tinygltf::Primitive& primitive : model_.meshes[size_t(index)].primitives) {
            if (!(primitive.mode == TINYGLTF_MODE_TRIANGLES || primitive.mode == -1)) {
                ++out_.skipped;
                continue;
            }
            if (!this->primitive(primitive, transform, normalMatrix, mirrored)) return false;
        }
        return true;
    }

    bool node(int index, const glm::dmat4& parent, int depth) {
        if (index < 0 || size_t(index) >= model_.nodes.size())
            return fail("node " + std::to_string(index) + " does not exist");
        if (depth > kMaxNodeDepth) return fail("the node hierarchy is deeper than 64 (a cycle?)");
        const tinygltf::Node& n = model_.nodes[size_t(index)];
        const glm::dmat4 transform = parent * localTransform(n);
        if (n.mesh >= 0 && !mesh(n.mesh, transform)) return false;
        for (const int child : n.children) {
            if (!node(child, transform, depth + 1)) return false;
        }
        return true;
    }

    const std::string& error() const { return error_; }

private:
    bool fail(const std::string& message) {
        error_ = message;
        return false;
    }

    bool primitive(const tinygltf::Primitive& p, const glm::dmat4& transform, const glm::dmat3& normalMatrix,
                   bool mirrored) {
        if (p.extensions.count("KHR_draco_mesh_compression"))
            return fail("Draco-compressed primitives (KHR_draco_mesh_compression) are not supported");
        const auto attribute = [&](const char* name) {
            const auto it = p.attributes.find(name);
            return it == p.attributes.end() ? -1 : it->second;
        };
        if (attribute("POSITION") < 0) return fail("a primitive has no POSITION");
        std::vector<float> positions, normals, uvs, colours;
        std::string error;
        if (!readFloatAccessor(model_, attribute("POSITION"), 3, positions, error)) return fail(error);
        const size_t count = positions.size() / 3;
        const auto optional = [&](const char* name, int components, std::vector<float>& into) {
            if (attribute(name) < 0) return true;
            if (!readFloatAccessor(model_, attribute(name), components, into, error)) return false;
            if (into.size() / size_t(components) != count) {
                error = std::string(name) + " has a different count from POSITION";
                return false;
            }
            return true;
        };
        if (!optional("NORMAL", 3, normals) || !optional("TEXCOORD_0", 2, uvs) ||
            !optional("COLOR_0", 4, colours))
            return fail(error);
        std::vector<uint32_t> indices;
        if (p.indices >= 0) {
            if (!readIndexAccessor(model_, p.indices, indices, error)) return fail(error);
        } else {
            indices.resize(count);
            for (size_t i = 0; i < count; ++i) indices[i] = uint32_t(i);
        }
        if (indices.size() % 3) return fail("a triangle primitive's index count is not a multiple of 3");
        for (const uint32_t i : indices) {
            if (i >= count) return fail("an index points past the primitive's vertices");
        }
        glm::vec4 factor(1.0f);
        if (p.material >= 0 && size_t(p.material) < model_.materials.size()) {
            const std::vector<double>& f =
                model_.materials[size_t(p.material)].pbrMetallicRoughness.baseColorFactor;
            if (f.size() == 4) factor = glm::vec4(f[0], f[1], f[2], f[3]);
        }
        const TextureSampler texture = baseColorTexture(model_, p.material);
        const glm::vec4 textureMean = texture.valid() && uvs.empty() ? texture.mean() : glm::vec4(1.0f);
        const uint32_t first = static_cast<uint32_t>(out_.positions.size());
        for (size_t i = 0; i < count; ++i) {
            out_.positions.push_back(glm::dvec3(
                transform * glm::dvec4(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2], 1.0)));
            out_.normals.push_back(
                normals.empty()
                    ? glm::dvec3(0.0)
                    : normalMatrix * glm::dvec3(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]));
            const glm::vec2 uv = uvs.empty() ? glm::vec2(0.0f) : glm::vec2(uvs[2 * i], uvs[2 * i + 1]);
            out_.uvs.push_back(uv);
            glm::vec4 colour = factor * textureMean;
            if (!colours.empty()) colour *= glm::make_vec4(&colours[4 * i]);
            if (texture.valid() && !uvs.empty()) colour *= texture.sample(uv);
            out_.colours.push_back(colour);
        }
        for (size_t t = 0; t < indices.size(); t += 3) {
            out_.indices.insert(out_.indices.end(),
                                {first + indices[t], first + indices[t + (mirrored ? 2 : 1)],
                                 first + indices[t + (mirrored ? 1 : 2)]});
        }
        if (out_.indices.size() / 3 > kMaxGltfTriangles)
            return fail("more than " + std::to_string(kMaxGltfTriangles) + " triangles");
        return true;
    }

    const tinygltf::Model& model_;
    Gathered& out_;
    std::string error_;
};

bool readModel(const std::string& path, tinygltf::Model& model, std::string& error) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
        error = "no such file";
        return false;
    }
    const uintmax_t bytes = std::filesystem::file_size(path, ec);
    if (ec || bytes > kMaxFileBytes) {
        error = ec ? "cannot read its size" : "larger than 1 GiB";
        return false;
    }
    char magic[4] = {};
    std::ifstream(path, std::ios::binary).read(magic, 4);
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    const bool binary = std::string_view(magic, 4) == "glTF";
    const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                           : loader.LoadASCIIFromFile(&model, &err, &warn, path);
    if (!ok) {
        while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
        error = std::string("not a readable glTF ") + (binary ? "binary" : "file") +
                (err.empty() ? "" : ": " + err);
        return false;
    }
    for (const std::string& required : model.extensionsRequired) {
        if (required == "KHR_draco_mesh_compression" || required == "EXT_meshopt_compression" ||
            required == "KHR_meshopt_compression") {
            error = "requires the extension " + required + ", which is not supported";
            return false;
        }
    }
    return true;
}

bool gather(const tinygltf::Model& model, Gathered& out, std::string& error) {
    Flattener flattener(model, out);
    bool ok = true;
    if (!model.nodes.empty()) {
        std::vector<int> roots;
        if (model.defaultScene >= 0 && size_t(model.defaultScene) < model.scenes.size()) {
            roots = model.scenes[size_t(model.defaultScene)].nodes;
        } else if (!model.scenes.empty()) {
            roots = model.scenes[0].nodes;
        } else {
            std::vector<bool> child(model.nodes.size(), false);
            for (const tinygltf::Node& n : model.nodes) {
                for (const int c : n.children) {
                    if (c >= 0 && size_t(c) < child.size()) child[size_t(c)] = true;
                }
            }
            for (size_t i = 0; i < child.size(); ++i) {
                if (!child[i]) roots.push_back(int(i));
            }
        }
        for (const int root : roots) ok = ok && flattener.node(root, glm::dmat4(1.0), 0);
    } else {
        for (size_t m = 0; m < model.meshes.size() && ok; ++m) ok = flattener.mesh(int(m), glm::dmat4(1.0));
    }
    if (!ok) error = flattener.error();
    return ok;
}

} // namespace

GltfLoadResult loadGltfMesh(const std::string& path, const std::string& shape, const glm::vec3& nominalSize) {
    GltfLoadResult result;
    const auto fail = [&](const std::string& what) {
        result.error = path + ": " + what;
        return result;
    };
    tinygltf::Model model;
    std::string error;
    if (!readModel(path, model, error)) return fail(error);
    Gathered g;
    if (!gather(model, g, error)) return fail(error);
    if (g.skipped) {
        result.warnings.push_back(path + ": " + std::to_string(g.skipped) +
                                  " primitive(s) that are not triangle lists were skipped");
    }
    if (g.indices.empty()) return fail("no triangles (only TRIANGLES primitives are read)");

    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
    for (const glm::dvec3& p : g.positions) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return fail("a position is not finite");
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    const glm::dvec3 extent = hi - lo;
    if (extent.x > kMaxGltfExtent || extent.y > kMaxGltfExtent || extent.z > kMaxGltfExtent)
        return fail("its bounds are larger than 1e6 m");
    const double scale = std::max(std::max(extent.x, extent.y), extent.z);
    if (!(extent.x > 1e-9 * scale) || !(extent.y > 1e-9 * scale) || !(scale > 0.0))
        return fail("its bounds are degenerate (flat in x or y), so it cannot span a scope");
    const bool flat = !(extent.z > 1e-9 * scale);
    // Metric nominal space: the model stretched to W x H x D (or its own depth proportion).
    glm::dvec3 nominal = glm::dvec3(nominalSize);
    if (!(nominal.z > 0.0))
        nominal.z = flat ? 0.0 : extent.z * 0.5 * (nominal.x / extent.x + nominal.y / extent.y);
    const glm::dvec3 stretch(nominal.x / extent.x, nominal.y / extent.y, flat ? 1.0 : nominal.z / extent.z);

    TerminalMesh& mesh = result.mesh;
    mesh.shape = shape;
    mesh.source = path;
    mesh.nominalSize = glm::vec3(nominal);
    mesh.indices = std::move(g.indices);
    mesh.vertices.resize(g.positions.size());
    std::vector<bool> missing(g.positions.size(), false);
    for (size_t i = 0; i < g.positions.size(); ++i) {
        const glm::dvec3 unit = (g.positions[i] - lo) / glm::dvec3(extent.x, extent.y, flat ? 1.0 : extent.z);
        glm::dvec3 n = g.normals[i] / stretch; // inverse transpose of the diagonal stretch
        if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) n = glm::dvec3(0.0);
        missing[i] = glm::length(n) == 0.0;
        const glm::vec4 c = glm::clamp(g.colours[i], 0.0f, 1.0f);
        mesh.vertices[i] = {glm::vec3(unit.x, unit.y, flat ? 0.0 : unit.z), glm::vec3(n), g.uvs[i],
                            packRgba(c.r, c.g, c.b, c.a)};
    }
    // Area-weighted face normals in metric nominal space where the file has none (or a zero one).
    for (size_t t = 0; t < mesh.indices.size(); t += 3) {
        const uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
        const glm::dvec3 pa = glm::dvec3(mesh.vertices[a].position) * nominal,
                         pb = glm::dvec3(mesh.vertices[b].position) * nominal,
                         pc = glm::dvec3(mesh.vertices[c].position) * nominal;
        const glm::dvec3 face = glm::cross(pb - pa, pc - pa);
        for (const uint32_t v : {a, b, c}) {
            if (missing[v]) mesh.vertices[v].normal += glm::vec3(face);
        }
    }
    for (MeshVertex& v : mesh.vertices) {
        const float length = glm::length(v.normal);
        v.normal = length > 0.0f && std::isfinite(length) ? v.normal / length : glm::vec3(0, 0, 1);
    }
    finalizeMesh(mesh);
    result.ok = true;
    return result;
}

} // namespace hexlod::render
