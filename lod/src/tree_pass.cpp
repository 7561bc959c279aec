#include "hexlod/lod/tree_pass.h"
#include "hexlod/lod/gpu_cull.h"
#include "hexlod/render/gl_api.h"

#include <map>

namespace hexlod::lod {

TreePass::~TreePass() {
    for (uint32_t buffer : {byId_, instances_, spheres_})
        if (buffer) gl::glDeleteBuffers(1, &buffer);
    if (vao_) gl::glDeleteVertexArrays(1, &vao_);
}

bool TreePass::init(const cells::BatchCatalog& catalog, const SceneImpostors* impostors,
                    const glm::dvec3& origin, std::string& error) {
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
        ranges_[b] = {uint32_t(instances.size()), uint32_t(batch.buildings.size())};
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
    std::vector<glm::vec4> spheres;
    for (const impostor::ImpostorAtlas& atlas : impostors->species) {
        atlases.push_back(&atlas);
        spheres.emplace_back(atlas.centre, atlas.radius);
    }
    const impostor::ViewLayout& layout = impostors->species.front().layout;
    impostor::ViewLookup lookup(layout);
    if (!textures_.upload(layout, atlases, lookup.buildTable(64), error)) return false;
    upload(spheres_, spheres);
    bytes_ += spheres.size() * sizeof(glm::vec4) + textures_.byteSize();
    render::ShaderLibrary library = lodShaderLibrary();
    program_ = render::ShaderProgram::build(library,
                                            {{render::ShaderStage::Vertex, "tree_billboard.vert"},
                                             {render::ShaderStage::Fragment, "tree_billboard.frag"}},
                                            "", error);
    if (!program_.valid()) return false;
    // The shader pulls its trees from the buffer; the core profile still wants a vertex array.
    gl::glCreateVertexArrays(1, &vao_);
    return true;
}

void TreePass::begin(const render::ShaderProgram& program) const {
    program.use();
    textures_.bind(program, 0);
    gl::glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, spheres_);
    gl::glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 13, instances_);
    gl::glBindVertexArray(vao_);
}

uint32_t TreePass::draw(uint32_t batch, bool allBillboards) const {
    const auto [first, count] = ranges_.at(batch);
    if (count == 0 || !vao_) return 0;
    program_.set("allBillboards", uint32_t(allBillboards));
    gl::glDrawArrays(GL_TRIANGLES, GLint(6 * first), GLsizei(6 * count));
    return count;
}

} // namespace hexlod::lod
