// Impostor baking: every view of a layout rendered in one framebuffer, one viewport per tile.
#include "hexlod/impostor/impostor_baker.h"
#include "hexlod/render/gl_api.h"
#include "hexlod/render/mesh_vertex_format.h"
#include "hexlod/render/render_shaders.h"

#include <Imath/half.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace hexlod::impostor {
namespace {

uint64_t hashBytes(uint64_t hash, const void* data, size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 0x100000001b3ull; // FNV-1a
    return hash;
}

// The orthographic view of the sphere (centre, radius) along `basis`: x and y of the image
// from right and up, clip z from depth so that nearer is smaller.
glm::mat4 viewProjection(const ViewBasis& basis, const glm::vec3& centre, float radius) {
    // Depth spans [-radius, radius]; a little slack keeps the sphere's poles off the clip planes.
    const float depthScale = 1.0f / (radius * 1.01f);
    glm::mat4 m(0.0f);
    auto row = [&m](int r, const glm::vec3& axis, float scale, const glm::vec3& origin) {
        m[0][r] = axis.x * scale;
        m[1][r] = axis.y * scale;
        m[2][r] = axis.z * scale;
        m[3][r] = -glm::dot(axis, origin) * scale;
    };
    row(0, basis.right, 1.0f / radius, centre);
    row(1, basis.up, 1.0f / radius, centre);
    row(2, -basis.forward, depthScale, centre);
    m[3][3] = 1.0f;
    return m;
}

// Fills empty texels of one tile from covered or already-filled neighbours, `passes` rings
// deep; alpha stays 0 and depth keeps its empty marker only where nothing reached.
void dilateTile(render::Image& albedo, render::Image& normalDepth, glm::uvec2 origin, uint32_t size,
                uint32_t passes) {
    std::vector<uint8_t> filled(size_t(size) * size);
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x)
            filled[y * size + x] = albedo.at(origin.x + x, origin.y + y)[3] > 0.0f;
    std::vector<uint8_t> next = filled;
    for (uint32_t pass = 0; pass < passes; ++pass) {
        bool changed = false;
        for (uint32_t y = 0; y < size; ++y) {
            for (uint32_t x = 0; x < size; ++x) {
                if (filled[y * size + x]) continue;
                glm::vec3 colour(0.0f), normal(0.0f);
                float depth = 0.0f;
                int count = 0;
                for (int dy = -1; dy <= 1; ++dy) {
                    for (int dx = -1; dx <= 1; ++dx) {
                        int nx = int(x) + dx, ny = int(y) + dy;
                        if (nx < 0 || ny < 0 || nx >= int(size) || ny >= int(size) || !filled[ny * size + nx])
                            continue;
                        const float* a = albedo.at(origin.x + nx, origin.y + ny);
                        const float* n = normalDepth.at(origin.x + nx, origin.y + ny);
                        colour += glm::vec3(a[0], a[1], a[2]);
                        normal += glm::vec3(n[0], n[1], n[2]);
                        depth += n[3];
                        ++count;
                    }
                }
                if (count == 0) continue;
                float* a = albedo.at(origin.x + x, origin.y + y);
                float* n = normalDepth.at(origin.x + x, origin.y + y);
                colour /= float(count);
                normal = glm::length(normal) > 0.0f ? glm::normalize(normal) : glm::vec3(0, 0, 1);
                // Stored as halves, as the atlas texels are, so a saved atlas reads back the same.
                for (int c = 0; c < 3; ++c) {
                    a[c] = float(half(colour[c]));
                    n[c] = float(half(normal[c]));
                }
                n[3] = float(half(depth / float(count)));
                next[y * size + x] = 1;
                changed = true;
            }
        }
        filled = next;
        if (!changed) break;
    }
}

// Averages samples x samples blocks into the output at `origin`: coverage is the share of
// covered samples, colour, normal and depth are averaged over the covered ones. Values are
// rounded to halves, as the atlas's GPU textures and EXR file hold them.
void downsample(const render::Image& albedoSamples, const render::Image& normalSamples, uint32_t samples,
                glm::uvec2 origin, render::Image& albedo, render::Image& normalDepth) {
    const uint32_t size = albedoSamples.width / samples;
    for (uint32_t y = 0; y < size; ++y) {
        for (uint32_t x = 0; x < size; ++x) {
            glm::vec4 colour(0.0f), normal(0.0f);
            uint32_t covered = 0;
            for (uint32_t sy = 0; sy < samples; ++sy) {
                for (uint32_t sx = 0; sx < samples; ++sx) {
                    const float* a = albedoSamples.at(x * samples + sx, y * samples + sy);
                    if (a[3] <= 0.0f) continue;
                    const float* n = normalSamples.at(x * samples + sx, y * samples + sy);
                    colour += glm::vec4(a[0], a[1], a[2], 0.0f);
                    normal += glm::vec4(n[0], n[1], n[2], n[3]);
                    ++covered;
                }
            }
            float* outAlbedo = albedo.at(origin.x + x, origin.y + y);
            float* outNormal = normalDepth.at(origin.x + x, origin.y + y);
            if (covered == 0) continue;
            colour /= float(covered);
            glm::vec3 n = glm::vec3(normal);
            n = glm::length(n) > 0.0f ? glm::normalize(n) : glm::vec3(0, 0, 1);
            for (int c = 0; c < 3; ++c) {
                outAlbedo[c] = float(half(colour[c]));
                outNormal[c] = float(half(n[c]));
            }
            outAlbedo[3] = float(half(float(covered) / float(samples * samples)));
            outNormal[3] = float(half(normal.w / float(covered)));
        }
    }
}

} // namespace

uint64_t bakeKey(uint64_t geometryHash, const glm::vec3& nominalSize, const ViewLayout& layout) {
    constexpr uint32_t kBakeFormat = 2; // bump when the baked images change for the same input
    uint64_t hash = 0xcbf29ce484222325ull;
    hash = hashBytes(hash, &kBakeFormat, sizeof kBakeFormat);
    hash = hashBytes(hash, &geometryHash, sizeof geometryHash);
    hash = hashBytes(hash, &nominalSize, sizeof nominalSize);
    const uint32_t fields[4] = {uint32_t(layout.sphere), layout.grid, layout.viewResolution, layout.padding};
    return hashBytes(hash, fields, sizeof fields);
}

BakeGeometry geometryFromMesh(const render::TerminalMesh& mesh) {
    BakeGeometry geometry;
    geometry.vertices = mesh.vertices;
    for (render::MeshVertex& v : geometry.vertices) v.position *= mesh.nominalSize;
    geometry.indices = mesh.indices;
    geometry.hash = hashBytes(mesh.contentHash, &mesh.nominalSize, sizeof mesh.nominalSize);
    return geometry;
}

void measureGeometry(const BakeGeometry& geometry, ImpostorAtlas& atlas) {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (uint32_t index : geometry.indices) {
        lo = glm::min(lo, geometry.vertices[index].position);
        hi = glm::max(hi, geometry.vertices[index].position);
    }
    atlas.boundsMin = lo;
    atlas.boundsMax = hi;
    atlas.centre = 0.5f * (lo + hi);
    atlas.radius = 0.5f * glm::length(hi - lo);
}

bool ImpostorBaker::init(std::string& error) {
    render::ShaderLibrary library = render::renderShaderLibrary();
    program_ = render::ShaderProgram::build(library,
                                            {{render::ShaderStage::Vertex, "shape_view.vert"},
                                             {render::ShaderStage::Fragment, "shape_view.frag"}},
                                            "", error);
    return program_.valid();
}

struct ImpostorBaker::Upload {
    GLuint vao = 0, buffers[2] = {0, 0};
    explicit Upload(const BakeGeometry& geometry) {
        gl::glCreateBuffers(2, buffers);
        gl::glNamedBufferStorage(buffers[0],
                                 GLsizeiptr(geometry.vertices.size() * sizeof(render::MeshVertex)),
                                 geometry.vertices.data(), 0);
        gl::glNamedBufferStorage(buffers[1], GLsizeiptr(geometry.indices.size() * sizeof(uint32_t)),
                                 geometry.indices.data(), 0);
        gl::glCreateVertexArrays(1, &vao);
        gl::glVertexArrayVertexBuffer(vao, 0, buffers[0], 0, sizeof(render::MeshVertex));
        gl::glVertexArrayElementBuffer(vao, buffers[1]);
        render::setMeshVertexFormat(vao, 0);
    }
    ~Upload() {
        gl::glDeleteVertexArrays(1, &vao);
        gl::glDeleteBuffers(2, buffers);
    }
};

bool ImpostorBaker::drawViews(const BakeGeometry& geometry, const ViewLayout& layout,
                              std::span<const glm::vec3> directions, uint32_t tileSize, uint32_t padding,
                              uint32_t columns, render::Image& albedo, render::Image& normalDepth,
                              std::string& error) {
    if (!program_.valid()) {
        error = "the impostor baker was not initialised";
        return false;
    }
    if (geometry.indices.empty()) {
        error = "nothing to bake: the geometry has no triangles";
        return false;
    }
    ImpostorAtlas frame;
    measureGeometry(geometry, frame);
    if (!(frame.radius > 0.0f) || !std::isfinite(frame.radius)) {
        error = "nothing to bake: the geometry has no extent";
        return false;
    }
    // One view at a time, supersampled, into a target of one view's inner area: memory stays
    // bounded by a view however large the atlas, and edges come out antialiased.
    const uint32_t inner = tileSize - 2 * padding, samples = kSupersampling;
    render::Framebuffer target;
    if (!render::Framebuffer::create({inner * samples, inner * samples, {GL_RGBA16F, GL_RGBA16F}, true},
                                     target, error)) {
        return false;
    }
    const uint32_t rows = uint32_t((directions.size() + columns - 1) / columns);
    albedo = render::Image(columns * tileSize, rows * tileSize, 4, 0.0f);
    normalDepth = render::Image(columns * tileSize, rows * tileSize, 4, 0.0f);
    for (size_t i = 3; i < normalDepth.pixels.size(); i += 4) normalDepth.pixels[i] = -1.0f;
    Upload upload(geometry);
    program_.use();
    gl::glEnable(GL_DEPTH_TEST);
    gl::glDepthFunc(GL_LESS);
    gl::glDisable(GL_CULL_FACE);
    gl::glDisable(GL_BLEND);
    for (size_t v = 0; v < directions.size(); ++v) {
        target.bind();
        target.clear(0.0f, 0.0f, 0.0f, 0.0f);
        target.clearAttachment(1, 0.0f, 0.0f, 0.0f, -1.0f);
        gl::glBindVertexArray(upload.vao);
        ViewBasis basis = viewBasis(layout.sphere, directions[v]);
        program_.set("shapeToClip", viewProjection(basis, frame.centre, frame.radius));
        program_.set("depthPlane", glm::vec4(basis.forward / frame.radius,
                                             -glm::dot(basis.forward, frame.centre) / frame.radius));
        gl::glDrawElements(GL_TRIANGLES, GLsizei(geometry.indices.size()), GL_UNSIGNED_INT, nullptr);
        gl::glBindVertexArray(0);
        const glm::uvec2 origin(uint32_t(v % columns) * tileSize + padding,
                                uint32_t(v / columns) * tileSize + padding);
        downsample(target.readColor(0), target.readColor(1), samples, origin, albedo, normalDepth);
    }
    return true;
}

bool ImpostorBaker::bake(const BakeGeometry& geometry, const ViewLayout& layout, ImpostorAtlas& out,
                         std::string& error) {
    if (!layout.validate(error)) return false;
    std::vector<glm::vec3> directions(layout.viewCount());
    for (uint32_t v = 0; v < layout.viewCount(); ++v) directions[v] = layout.direction(v);
    ImpostorAtlas atlas;
    if (!drawViews(geometry, layout, directions, layout.viewResolution, layout.padding, layout.grid,
                   atlas.albedo, atlas.normalDepth, error)) {
        return false;
    }
    atlas.layout = layout;
    measureGeometry(geometry, atlas);
    for (uint32_t v = 0; v < layout.viewCount(); ++v) {
        dilateTile(atlas.albedo, atlas.normalDepth, layout.tileOrigin(v), layout.viewResolution,
                   layout.padding + 2);
    }
    out = std::move(atlas);
    return true;
}

bool ImpostorBaker::renderDirection(const BakeGeometry& geometry, const ViewLayout& layout,
                                    const glm::vec3& direction, render::Image& albedo,
                                    render::Image& normalDepth, std::string& error) {
    if (!layout.validate(error)) return false;
    if (!(glm::length(direction) > 0.0f)) {
        error = "the direction has no length";
        return false;
    }
    glm::vec3 d = glm::normalize(direction);
    return drawViews(geometry, layout, std::span<const glm::vec3>(&d, 1), layout.innerResolution(), 0, 1,
                     albedo, normalDepth, error);
}

} // namespace hexlod::impostor
