#include "hexlod/lod/tree_pass.h"
#include "hexlod/lod/cull_inputs.h"
#include "hexlod/lod/gpu_cull.h"
#include "hexlod/lod/occlusion_tests.h"
#include "hexlod/lod/page_bounds.h"
#include "hexlod/lod/tree_view_averages.h"
#include "hexlod/render/gl_api.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <limits>
#include <map>

namespace hexlod::lod {
namespace {

constexpr uint32_t kTreeChunk = 32;
// A chunk is larger than a tree: worth more tile lookups (as an arena page).
constexpr uint32_t kChunkMaxTiles = 256;

// Interleaves the bits of two 16-bit values: neighbours in the plane stay near in the order.
uint32_t morton(uint32_t x, uint32_t y) {
    auto spread = [](uint32_t v) {
        v &= 0xffffu;
        v = (v | (v << 8)) & 0x00ff00ffu;
        v = (v | (v << 4)) & 0x0f0f0f0fu;
        v = (v | (v << 2)) & 0x33333333u;
        return (v | (v << 1)) & 0x55555555u;
    };
    return spread(x) | (spread(y) << 1);
}

// The sphere around points `centres[i]` each grown by radii[i].
glm::vec4 enclose(const std::vector<glm::vec3>& centres, const std::vector<float>& radii) {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    for (const glm::vec3& c : centres) lo = glm::min(lo, c), hi = glm::max(hi, c);
    const glm::vec3 centre = 0.5f * (lo + hi);
    float radius = 0.0f;
    for (size_t i = 0; i < centres.size(); ++i)
        radius = std::max(radius, glm::length(centres[i] - centre) + radii[i]);
    // Padded as the arena's pages are: the tests that use it run in float.
    return {centre, radius + 0.01f + 1e-5f * (radius + glm::length(centre))};
}

} // namespace

TreePass::~TreePass() {
    for (uint32_t buffer : {byId_, instances_, spheres_, boxes_, viewAverages_})
        if (buffer) gl::glDeleteBuffers(1, &buffer);
    if (vao_) gl::glDeleteVertexArrays(1, &vao_);
}

bool TreePass::init(const cells::BatchCatalog& catalog, const SceneImpostors* impostors,
                    const glm::dvec3& origin, bool fitToBoxes, std::string& error) {
    origin_ = origin;
    const scene::BuiltScene& scene = catalog.scene();
    if (scene.treeGrammars.empty()) return true;
    const uint32_t buildingGrammars = uint32_t(scene.buildingGrammars.size());
    // Species by (tree grammar, resolved parameters), as the impostor baker numbered them.
    std::map<std::pair<uint32_t, std::vector<float>>, float> speciesOf;
    if (impostors) {
        for (size_t s = 0; s < impostors->speciesParameters.size(); ++s)
            speciesOf[{impostors->speciesGrammar[s], impostors->speciesParameters[s]}] = float(s);
    }
    size_t byId = 0;
    for (const scene::GrammarBuildings& grammar : scene.treeGrammars)
        for (const grammar::BuildingInput& tree : grammar.buildings)
            byId = std::max<size_t>(byId, tree.id + 1);
    trees_.assign(byId, glm::vec4(0.0f, 0.0f, 0.0f, -1.0f));
    std::vector<glm::vec4> instances;
    ranges_.assign(catalog.batchCount(), {0u, 0u});
    for (uint32_t b = 0; b < catalog.batchCount(); ++b) {
        const cells::Batch& batch = catalog.batch(b);
        if (batch.grammar < buildingGrammars) continue;
        const scene::GrammarBuildings& grammar = catalog.grammar(batch.grammar);
        const size_t first = instances.size();
        ranges_[b] = {uint32_t(first), uint32_t(batch.buildings.size())};
        for (uint32_t member : batch.buildings) {
            const grammar::BuildingInput& tree = grammar.buildings[member];
            glm::dvec2 centre(0.0);
            for (const glm::dvec2& p : tree.footprint) centre += p;
            centre /= double(std::max<size_t>(tree.footprint.size(), 1));
            auto species = speciesOf.find({batch.grammar, tree.parameters});
            const glm::vec4 t(glm::vec3(glm::dvec3(centre, tree.baseElevation) - origin),
                              species == speciesOf.end() ? -1.0f : species->second);
            trees_[tree.id] = t;
            instances.push_back(t);
        }
        // Neighbours next to each other, so that a chunk is a patch of the cell.
        glm::vec2 lo(std::numeric_limits<float>::max());
        for (size_t i = first; i < instances.size(); ++i) lo = glm::min(lo, glm::vec2(instances[i]));
        const auto key = [&](const glm::vec4& tree) {
            // Metres from the batch's corner; anything not a number sorts first.
            const auto grid = [](float v) { return v > 0.0f ? uint32_t(std::min(v, 65535.0f)) : 0u; };
            return morton(grid(tree.x - lo.x), grid(tree.y - lo.y));
        };
        std::sort(instances.begin() + std::ptrdiff_t(first), instances.end(),
                  [&](const auto& a, const auto& c) { return key(a) < key(c); });
    }
    // Without trees each buffer holds one unused element, since the cull pass binds the tree
    // buffer whatever the scene and GL has no empty buffer storage; they count as nothing.
    auto upload = [](uint32_t& buffer, const std::vector<glm::vec4>& data) {
        gl::glCreateBuffers(1, &buffer);
        gl::glNamedBufferStorage(buffer, GLsizeiptr(std::max<size_t>(data.size(), 1) * sizeof(glm::vec4)),
                                 data.empty() ? nullptr : data.data(), 0);
    };
    upload(byId_, trees_);
    upload(instances_, instances);
    bytes_ = (trees_.size() + instances.size()) * sizeof(glm::vec4);
    if (!impostors || impostors->species.empty()) return true;

    std::vector<const impostor::ImpostorAtlas*> atlases;
    std::vector<glm::vec4> spheres, boxes;
    for (const impostor::ImpostorAtlas& atlas : impostors->species) {
        atlases.push_back(&atlas);
        spheres.emplace_back(atlas.centre, atlas.radius);
        // The cube around the sphere gives each billboard the sphere's square whole.
        const glm::vec3 reach(atlas.radius);
        boxes.emplace_back(fitToBoxes ? atlas.boundsMin : atlas.centre - reach, 0.0f);
        boxes.emplace_back(fitToBoxes ? atlas.boundsMax : atlas.centre + reach, 0.0f);
    }
    const impostor::ViewLayout& layout = impostors->species.front().layout;
    impostor::ViewLookup lookup(layout);
    if (!textures_.upload(layout, atlases, lookup.buildTable(impostor::kSpeciesTableResolution), error))
        return false;
    upload(spheres_, spheres);
    upload(boxes_, boxes);
    std::vector<glm::vec4> averages;
    for (const impostor::ImpostorAtlas& atlas : impostors->species) {
        const std::vector<glm::vec4> species = treeViewAverages(atlas);
        averages.insert(averages.end(), species.begin(), species.end());
    }
    upload(viewAverages_, averages);
    bytes_ += (spheres.size() + boxes.size() + averages.size()) * sizeof(glm::vec4) + textures_.byteSize();
    buildChunks(instances, spheres);
    render::ShaderLibrary library = lodShaderLibrary();
    for (uint32_t flat = 0; flat < 2; ++flat) {
        billboardPrograms_[flat] =
            render::ShaderProgram::build(library,
                                         {{render::ShaderStage::Vertex, "tree_billboard.vert"},
                                          {render::ShaderStage::Fragment, "tree_billboard.frag"}},
                                         "#define TREE_BILLBOARD_FLAT " + std::to_string(flat) + "\n", error);
        if (!billboardPrograms_[flat].valid()) return false;
    }
    pointProgram_ = render::ShaderProgram::build(
        library,
        {{render::ShaderStage::Vertex, "tree_point.vert"}, {render::ShaderStage::Fragment, "point.frag"}}, "",
        error);
    if (!pointProgram_.valid()) return false;
    // The shaders pull their trees from the buffer; the core profile still wants a vertex array.
    gl::glCreateVertexArrays(1, &vao_);
    return true;
}

void TreePass::buildChunks(const std::vector<glm::vec4>& instances,
                           const std::vector<glm::vec4>& speciesSpheres) {
    chunkRanges_.assign(ranges_.size(), {0u, 0u});
    std::vector<glm::vec3> centres, roots;
    std::vector<float> radii, zero;
    for (size_t b = 0; b < ranges_.size(); ++b) {
        const auto [first, count] = ranges_[b];
        chunkRanges_[b].first = uint32_t(chunks_.size());
        for (uint32_t c = first; c < first + count; c += kTreeChunk) {
            Chunk chunk;
            chunk.first = c;
            chunk.count = std::min(kTreeChunk, first + count - c);
            centres.clear(), roots.clear(), radii.clear();
            for (uint32_t i = c; i < c + chunk.count; ++i) {
                const glm::vec4& tree = instances[i];
                // A tree of no species is never a billboard: its point still bounds the chunk.
                const glm::vec4 species = tree.w < 0.0f ? glm::vec4(0.0f) : speciesSpheres[size_t(tree.w)];
                roots.emplace_back(tree);
                centres.push_back(glm::vec3(tree) + glm::vec3(species));
                radii.push_back(species.w);
            }
            zero.assign(roots.size(), 0.0f);
            chunk.sphere = enclose(centres, radii);
            chunk.roots = enclose(roots, zero);
            chunk.minRadius = *std::min_element(radii.begin(), radii.end());
            chunk.maxRadius = *std::max_element(radii.begin(), radii.end());
            chunks_.push_back(chunk);
        }
        chunkRanges_[b].second = uint32_t(chunks_.size()) - chunkRanges_[b].first;
    }
    bytes_ += chunks_.size() * sizeof(Chunk);
}

void TreePass::Ranges::add(uint32_t first, uint32_t count) {
    // Chunks follow each other in the buffer: adjacent ones make one range.
    if (!counts.empty() && firsts.back() + counts.back() == int32_t(first))
        counts.back() += int32_t(count);
    else
        firsts.push_back(int32_t(first)), counts.push_back(int32_t(count));
}

std::pair<uint32_t, uint32_t> TreePass::prepare(const std::vector<std::pair<uint32_t, bool>>& batches,
                                                const TreeFrame& frame) {
    for (Ranges* ranges : {billboardRanges_[0], billboardRanges_[1], pointRanges_})
        ranges[0].clear(), ranges[1].clear();
    if (!vao_) return {0, 0};
    const shared::CullFrame& cull = *frame.cull;
    // cull.trees: x, the squared distance from which a tree is far (< 0: never); yzw, the
    // trees' origin minus the camera.
    const float cut = cull.trees.x;
    // tree_billboard.vert's form per tree, by its sphere's centre: flat from this squared distance.
    const float flatFrom = cull.lodDistance.y;
    const glm::vec3 offset(cull.trees.y, cull.trees.z, cull.trees.w);
    uint32_t billboards = 0, points = 0;
    for (const auto& [batch, allFar] : batches) {
        if (!allFar && cut < 0.0f) continue;
        const auto [firstChunk, chunkCount] = chunkRanges_.at(batch);
        for (uint32_t c = firstChunk; c < firstChunk + chunkCount; ++c) {
            const Chunk& chunk = chunks_[c];
            // Every root nearer than the cut: every tree is geometry, drawn by the terminal passes.
            const float farthestRoot = glm::length(glm::vec3(chunk.roots) + offset) + chunk.roots.w;
            if (!allFar && farthestRoot * farthestRoot < cut) continue;
            if (!pageMayBeVisible(chunk.sphere, offset, cull)) continue;
            const glm::vec3 centre = glm::vec3(chunk.sphere) + offset;
            if (tilesHideSphere(cull, frame.occlusionTiles, glm::vec4(centre, chunk.sphere.w),
                                kChunkMaxTiles))
                continue;
            // tree_size.glsl per tree; here with a margin, so that a chunk left to one form
            // holds no tree of the other.
            const float nearest = std::max(glm::length(centre) - chunk.sphere.w, 0.0f);
            const float farthest = glm::length(centre) + chunk.sphere.w;
            const bool anyBillboard =
                2.0f * chunk.maxRadius * frame.screenScale >= 0.99f * frame.pointDiameter * nearest;
            const bool anyPoint =
                2.0f * chunk.minRadius * frame.screenScale < 1.01f * frame.pointDiameter * farthest;
            if (anyBillboard) {
                // Each form that may hold one of the chunk's trees, with a margin.
                if (nearest * nearest < 1.01f * flatFrom)
                    billboardRanges_[0][allFar].add(chunk.first, chunk.count);
                if (farthest * farthest >= 0.99f * flatFrom)
                    billboardRanges_[1][allFar].add(chunk.first, chunk.count);
                billboards += chunk.count;
            }
            if (anyPoint) pointRanges_[allFar].add(chunk.first, chunk.count), points += chunk.count;
        }
    }
    return {billboards, points};
}

uint32_t TreePass::drawRanges(const render::ShaderProgram& program, const TreeFrame& frame,
                              const Ranges (&ranges)[2], bool points) {
    if (ranges[0].counts.empty() && ranges[1].counts.empty()) return 0;
    program.use();
    textures_.bind(program, 0);
    program.set("treeScreenScale", frame.screenScale);
    program.set("treePointDiameter", frame.pointDiameter);
    gl::glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, spheres_);
    gl::glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 13, instances_);
    gl::glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 15, viewAverages_);
    gl::glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 16, boxes_);
    gl::glBindVertexArray(vao_);
    if (points) gl::glEnable(GL_PROGRAM_POINT_SIZE);
    uint32_t draws = 0;
    for (uint32_t allFar = 0; allFar < 2; ++allFar) {
        if (ranges[allFar].counts.empty()) continue;
        program.set("allBillboards", allFar);
        const Ranges& drawn = ranges[allFar];
        if (points) {
            gl::glMultiDrawArrays(GL_POINTS, drawn.firsts.data(), drawn.counts.data(),
                                  GLsizei(drawn.counts.size()));
        } else {
            // Six indices a tree from the start of the quads, the base vertex four a tree.
            if (quads_.reserve(uint64_t(*std::max_element(drawn.counts.begin(), drawn.counts.end()))))
                gl::glVertexArrayElementBuffer(vao_, quads_.buffer());
            std::vector<GLsizei> counts;
            std::vector<GLint> baseVertices;
            for (size_t r = 0; r < drawn.counts.size(); ++r) {
                counts.push_back(6 * drawn.counts[r]);
                baseVertices.push_back(4 * drawn.firsts[r]);
            }
            const std::vector<const void*> offsets(counts.size(), nullptr);
            gl::glMultiDrawElementsBaseVertex(GL_TRIANGLES, counts.data(), GL_UNSIGNED_INT, offsets.data(),
                                              GLsizei(counts.size()), baseVertices.data());
        }
        ++draws;
    }
    if (points) gl::glDisable(GL_PROGRAM_POINT_SIZE);
    gl::glBindVertexArray(0);
    return draws;
}

uint32_t TreePass::drawBillboards(const TreeFrame& frame) {
    // The blended form first: the flat form's fragments behind it are then rejected unshaded.
    return drawRanges(billboardPrograms_[0], frame, billboardRanges_[0], false) +
           drawRanges(billboardPrograms_[1], frame, billboardRanges_[1], false);
}

uint32_t TreePass::drawPoints(const TreeFrame& frame) {
    return drawRanges(pointProgram_, frame, pointRanges_, true);
}

} // namespace hexlod::lod
