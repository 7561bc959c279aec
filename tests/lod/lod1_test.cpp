// LOD1's per-pixel grammar: the CPU walk finds the terminals the terminal set holds, and the
// GLSL interpreter finds what the CPU walk finds, pixel for pixel.
#include "../render/gl_fixture.h"
#include "test_city.h"

#include "hexlod/lod/gpu_cull.h"
#include "hexlod/lod/lod1_codegen.h"
#include "hexlod/lod/lod1_elements.h"
#include "hexlod/lod/lod1_query.h"
#include "hexlod/lod/volume_vertex.h"
#include "hexlod/render/base_volume_mesh.h"
#include "hexlod/render/framebuffer.h"

#include <glm/gtc/matrix_transform.hpp>

#include <array>
#include <filesystem>
#include <fstream>
#include <random>

#include <unistd.h>

namespace hexlod::lod {
namespace {

// The building of an element of `set`.
uint32_t buildingOf(const grammar::ExtrudedSet& set, uint32_t element) {
    for (uint32_t b = 0; b < set.buildings.size(); ++b) {
        const auto& building = set.buildings[b];
        if (element >= building.firstElement && element < building.firstElement + building.elementCount)
            return b;
    }
    return 0;
}

class Lod1Test : public ::testing::Test {
protected:
    static void SetUpTestSuite() { city_ = new testing::TestCity(testing::makeCity(60, 0)); }
    static void TearDownTestSuite() { delete city_; }
    static testing::TestCity* city_;
};
testing::TestCity* Lod1Test::city_ = nullptr;

TEST_F(Lod1Test, EveryTerminalTheWalkFindsIsInTheTerminalSet) {
    const cells::BatchCatalog& catalog = *city_->catalog;
    std::mt19937 random(9);
    uint64_t samples = 0, terminals = 0, matched = 0;
    for (uint32_t b = 0; b < catalog.batchCount(); ++b) {
        const grammar::BatchResult result = catalog.expand(b);
        const grammar::CompiledGrammar& g = catalog.grammar(catalog.batch(b).grammar).grammar;
        std::vector<grammar::Terminal> set;
        for (const auto& record : result.terminals.records) set.push_back(grammar::unpackTerminal(record));
        const grammar::ExtrudedSet& extruded = result.extruded;
        for (uint32_t e = 0; e < extruded.elements.size(); ++e) {
            const grammar::ExtrudedElement& element = extruded.elements[e];
            if (!(element.size.x > 0.5f && element.size.y > 0.5f)) continue; // roof edges: no face
            const uint32_t building = buildingOf(extruded, e);
            std::uniform_real_distribution<float> u(0.0f, element.size.x), v(0.0f, element.size.y);
            for (int k = 0; k < 12; ++k) {
                const glm::vec2 point(u(random), v(random));
                const Lod1Hit hit = lod1Query(g, extruded, building, e, point, catalog.scene().config.seed);
                ++samples;
                if (hit.outcome != Lod1Outcome::Terminal) continue;
                ++terminals;
                const glm::vec3 corner =
                    element.origin + element.axisX * hit.scopeOrigin.x + element.axisY * hit.scopeOrigin.y;
                for (const grammar::Terminal& t : set) {
                    if (t.shape != hit.shape || t.building != extruded.buildings[building].building) continue;
                    if (glm::length(t.position - corner) > 2e-3f * std::max(1.0f, glm::length(corner)))
                        continue;
                    if (std::abs(t.size.x - hit.scopeSize.x) > 2e-3f * hit.scopeSize.x + 1e-3f) continue;
                    if (std::abs(t.size.y - hit.scopeSize.y) > 2e-3f * hit.scopeSize.y + 1e-3f) continue;
                    ++matched;
                    break;
                }
            }
        }
    }
    ASSERT_GT(samples, 1000u);
    // Facades are tiled by terminals (walls included), so nearly every point finds one...
    EXPECT_GT(double(terminals) / double(samples), 0.9) << terminals << " of " << samples;
    // ...and every one it finds is a terminal of the set, at the same place and size.
    EXPECT_EQ(matched, terminals);
}

TEST_F(Lod1Test, BytecodeTranslatesToGlslInTheSameOrder) {
    const grammar::CompiledGrammar& g = city_->catalog->grammar(1).grammar; // residential
    std::string all = generateLod1Grammar(g);
    EXPECT_NE(all.find("float lod1Argument("), std::string::npos);
    EXPECT_NE(all.find("lod1RuleKey"), std::string::npos);
    // Every argument of a face subdivision or a pick becomes one case; the arguments of the
    // ops that end the walk (Extrude, Shape...) none, as the walk never evaluates them.
    uint32_t evaluated = 0, mostArguments = 1;
    for (const grammar::CompiledRule& rule : g.rules) {
        const bool walks = rule.op == grammar::RuleOp::Cond || rule.op == grammar::RuleOp::Choose ||
                           ((rule.op == grammar::RuleOp::Split || rule.op == grammar::RuleOp::Repeat) &&
                            rule.axis != grammar::Axis::Z);
        if (walks) mostArguments = std::max(mostArguments, rule.argumentCount);
        for (uint32_t a = rule.firstArgument; a < rule.firstArgument + rule.argumentCount; ++a) {
            const bool found = all.find("case " + std::to_string(a) + "u: return") != std::string::npos;
            EXPECT_EQ(found, walks) << grammar::ruleOpName(rule.op) << " argument " << a;
            evaluated += walks;
        }
    }
    EXPECT_GT(evaluated, 0u);
    EXPECT_LT(evaluated, g.arguments.size());
    EXPECT_NE(all.find("#define LOD1_MAX_ARGUMENTS " + std::to_string(mostArguments) + "\n"),
              std::string::npos);
    // rand() keeps its call site as the key's last word.
    bool sawRandom = false;
    for (const grammar::Expression& e : g.expressions) {
        const std::string glsl = expressionToGlsl(g, e);
        if (glsl.find("lod1Combine(randomKey") != std::string::npos) sawRandom = true;
    }
    EXPECT_TRUE(sawRandom);
}

// llvmpipe evaluates every case of lod1Argument for each argument (masked), so the cases must
// not read the parameter buffer: lod1LoadParameters reads each parameter the grammar uses once.
TEST_F(Lod1Test, ArgumentsReadParametersLoadedOncePerPixel) {
    const grammar::CompiledGrammar& g = city_->catalog->grammar(1).grammar; // residential
    const std::string all = generateLod1Grammar(g);
    const size_t load = all.find("void lod1LoadParameters(uint first)");
    const size_t arguments = all.find("float lod1Argument(");
    ASSERT_NE(load, std::string::npos);
    ASSERT_NE(arguments, std::string::npos);
    EXPECT_EQ(all.find("lod1Params[", arguments), std::string::npos);
    const std::string loads = all.substr(load, arguments - load);
    for (size_t p = 0; p < g.params.size(); ++p) {
        const std::string read = "lod1Params[first + " + std::to_string(p) + "u]";
        const bool used =
            all.find("lod1Parameter[" + std::to_string(p) + "]", arguments) != std::string::npos;
        EXPECT_EQ(loads.find(read) != std::string::npos, used) << g.params[p].name;
    }
}

class Lod1GpuTest : public render::GlTest {};

// The LOD1 program as the renderer builds it, over a grammar's generated GLSL.
render::ShaderProgram lod1Program(const std::string& grammarGlsl, std::string& error) {
    render::ShaderLibrary library = lodShaderLibrary();
    library.add("lod1_grammar.glsl", grammarGlsl);
    return render::ShaderProgram::build(
        library, {{render::ShaderStage::Vertex, "volume.vert"}, {render::ShaderStage::Fragment, "lod1.frag"}},
        "", error);
}

// The generated interpreter links whatever parameters a grammar has: none at all, or one no
// expression reads (lod1LoadParameters then loads nothing, or leaves it out).
TEST_F(Lod1GpuTest, InterpretersLinkWithoutParametersOrWithUnreadOnes) {
    const char* sources[] = {
        "shape wall (width = 1, height = 1, depth = 0, depth_ratio = 0, triangles = 2);\n"
        "Lot -> Extrude(9) { Facade, Roof };\n"
        "Facade -> Split(y, ~1, 3) { Body, Wall };\n"
        "Body -> Repeat(x, 2.5, fit) { Wall };\n"
        "Wall -> Shape(wall);\nRoof -> NULL;\n",
        "param unused = 1 in [0, 2];\nparam tile = 2.5 in [1, 5];\n"
        "shape wall (width = 1, height = 1, depth = 0, depth_ratio = 0, triangles = 2);\n"
        "Lot -> Extrude(9) { Facade, Roof };\n"
        "Facade -> Repeat(x, tile, fit) { Wall };\n"
        "Wall -> Shape(wall);\nRoof -> NULL;\n",
    };
    for (const char* source : sources) {
        grammar::DiagnosticList diagnostics;
        const grammar::CompiledGrammar g = grammar::compileGrammar(source, "test.grammar", diagnostics);
        ASSERT_FALSE(g.rules.empty()) << source;
        const std::string glsl = generateLod1Grammar(g);
        EXPECT_EQ(glsl.find("lod1Params[first + 0u]"), std::string::npos) << "no expression reads 'unused'";
        std::string error;
        render::ShaderProgram program = lod1Program(glsl, error);
        EXPECT_TRUE(program.valid()) << error << "\n" << glsl;
    }
}

// What the GLSL walk found, against the CPU walk, over the pixels of one facade.
struct WalkComparison {
    uint64_t compared = 0, agreed = 0;
    std::array<uint64_t, 3> outcomes{}; // the CPU walk's, by Lod1Outcome
};

// Draws batch `batch`'s walls with LOD1, looking at its first element's facade straight on
// from 40 m in front of its middle, and compares, for every third covered pixel each way,
// what the GLSL walk found with the CPU walk at the point the pixel reports.
void compareWalks(const cells::BatchCatalog& catalog, uint32_t batch, WalkComparison& result) {
    const uint32_t grammarIndex = catalog.batch(batch).grammar;
    const grammar::CompiledGrammar& g = catalog.grammar(grammarIndex).grammar;
    const grammar::ExtrudedSet extruded = catalog.expandExtruded(batch);
    const render::TerminalMesh shell = render::buildBaseVolumes(extruded, 0.0f);
    const std::vector<GpuLod1Element> elements = packLod1Elements(extruded, catalog.scene().config.seed);
    ASSERT_FALSE(elements.empty());

    std::string error;
    render::ShaderProgram program = lod1Program(generateLod1Grammar(g), error);
    ASSERT_TRUE(program.valid()) << error;

    // Look at the first element's facade straight on, from 40 m in front of its middle.
    const grammar::ExtrudedElement& first = extruded.elements[0];
    const glm::vec3 normal = glm::normalize(glm::cross(first.axisX, first.axisY));
    const glm::vec3 middle =
        first.origin + first.axisX * (0.5f * first.size.x) + first.axisY * (0.5f * first.size.y);
    const glm::vec3 eye = middle + normal * 40.0f;
    const uint32_t size = 128;
    render::Framebuffer target;
    ASSERT_TRUE(render::Framebuffer::create({size, size, {GL_RGBA16F, GL_RGBA32F}, true}, target, error))
        << error;
    // Frame block: camera-relative (the eye at the origin) view and projection.
    struct {
        glm::mat4 viewProjection;
        glm::vec4 sun, sunColour, sky, viewport;
    } frame;
    frame.viewProjection = glm::perspective(0.9f, 1.0f, 1.0f, 500.0f) *
                           glm::lookAt(glm::vec3(0.0f), middle - eye, glm::vec3(0, 0, 1));
    frame.sun = glm::vec4(0, 0, 1, 0.4f);
    frame.sunColour = glm::vec4(1.0f);
    frame.sky = glm::vec4(0.5f, 0.5f, 0.5f, 0.0f);
    frame.viewport = glm::vec4(float(size), float(size), 1.0f / float(size), 1.0f / float(size));
    GLuint buffers[3];
    gl::glCreateBuffers(3, buffers);
    gl::glNamedBufferStorage(buffers[0], sizeof frame, &frame, 0);
    gl::glNamedBufferStorage(buffers[1], GLsizeiptr(elements.size() * sizeof(GpuLod1Element)),
                             elements.data(), 0);
    gl::glNamedBufferStorage(buffers[2], GLsizeiptr(extruded.parameters.size() * sizeof(float)),
                             extruded.parameters.data(), 0);
    VolumeBuffers shellBuffers = uploadVolumeMesh(shell); // as VolumeCache uploads it
    gl::glBindBufferBase(GL_UNIFORM_BUFFER, 1, buffers[0]);
    gl::glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 12, buffers[1]);
    gl::glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 11, buffers[2]);
    target.bind();
    target.clear(0, 0, 0, 0);
    gl::glEnable(GL_DEPTH_TEST);
    gl::glDepthFunc(GL_LESS);
    program.use();
    program.set("cellOffset", -eye);
    program.set("lod0Blend", 0.0f);
    program.set("shapeBase", 0u);
    gl::glBindVertexArray(shellBuffers.vao);
    gl::glDrawElements(GL_TRIANGLES, GLsizei(shell.indices.size()), shellBuffers.indexType, nullptr);
    gl::glBindVertexArray(0);
    render::Image ids = target.readColor(1);
    releaseVolumeMesh(shellBuffers);
    gl::glDeleteBuffers(3, buffers);

    // The point each pixel reports in the test output is recomputed here from its ray.
    const glm::mat4 inverse = glm::inverse(frame.viewProjection);
    uint64_t compared = 0, agreed = 0;
    for (uint32_t y = 0; y < size; y += 3) {
        for (uint32_t x = 0; x < size; x += 3) {
            const float* id = ids.at(x, y);
            if (id[0] == 0.0f) continue; // no wall, or a cap
            // The ray through the pixel centre, intersected with the first element's plane.
            const glm::vec2 ndc((x + 0.5f) / size * 2 - 1, 1 - (y + 0.5f) / size * 2);
            glm::vec4 far = inverse * glm::vec4(ndc, 1.0f, 1.0f);
            const glm::vec3 direction = glm::normalize(glm::vec3(far) / far.w);
            const float t = glm::dot(first.origin - eye, normal) / glm::dot(direction, normal);
            const glm::vec3 local = eye + direction * t - first.origin;
            const glm::vec2 point(glm::dot(local, first.axisX), glm::dot(local, first.axisY));
            if (point.x < 0.05f || point.y < 0.05f || point.x > first.size.x - 0.05f ||
                point.y > first.size.y - 0.05f)
                continue;
            const Lod1Hit cpu =
                lod1Query(g, extruded, buildingOf(extruded, 0), 0, point, catalog.scene().config.seed);
            ++compared;
            ++result.outcomes.at(size_t(cpu.outcome));
            if (uint32_t(id[0]) == uint32_t(cpu.outcome) + 1 &&
                (cpu.outcome != Lod1Outcome::Terminal || uint32_t(id[1]) == cpu.shape)) {
                ++agreed;
            }
        }
    }
    result.compared = compared;
    result.agreed = agreed;
}

TEST_F(Lod1GpuTest, TheGlslWalkFindsWhatTheCpuWalkFinds) {
    testing::TestCity city = testing::makeCity(30, 0);
    const cells::BatchCatalog& catalog = *city.catalog;
    uint32_t batch = 0;
    while (batch < catalog.batchCount() &&
           catalog.grammar(catalog.batch(batch).grammar).name != "residential")
        ++batch;
    ASSERT_LT(batch, catalog.batchCount());
    WalkComparison walks;
    compareWalks(catalog, batch, walks);
    ASSERT_GT(walks.compared, 200u);
    // Pixels on a boundary between two terminals may fall either side of it: allow 2 %.
    EXPECT_GT(double(walks.agreed) / double(walks.compared), 0.98)
        << walks.agreed << " of " << walks.compared;
}

// A facade that peels one metre every two steps, 60 m tall: the walk reaches a terminal up to
// the step limit (32 m up) and stops above it, on the GPU where the CPU does. The metre under
// the limit is chosen in the limit's last step, which must stop too.
TEST_F(Lod1GpuTest, BothWalksStopAtTheSameStepLimit) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("hexlod_lod1_steps_" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "deep.grammar") << "param floors = 1 in [1, 300];\n"
                                           "shape wall (width = 1, height = 1, depth = 0, depth_ratio = 0, "
                                           "triangles = 2);\n"
                                           "extruded_set Facade;\n"
                                           "Lot -> Extrude(60) { Facade, Roof };\n"
                                           "Facade -> Cond(height > 1) { Peel, Wall };\n"
                                           "Peel -> Split(y, 1, ~1) { Wall, Facade };\n"
                                           "Wall -> Shape(wall);\nRoof -> NULL;\n";
    const std::string scene = R"({"name": "steps", "seed": 3, "cell_size": 120,
  "grammars": {"deep": {"file": ")" +
                              (dir / "deep.grammar").string() + R"("}},
  "buildings": [{"source": "procedural", "count": 2, "block_size": 90, "street_width": 12,
    "park_share": 0, "districts": [{"grammar": "deep", "share": 1, "floors": [1, 1], "lot": [16, 16]}]}]})";
    scene::SceneConfig config;
    scene::BuiltScene built;
    std::string error;
    const bool builtScene = scene::parseSceneConfig(scene, "steps.json", HEXLOD_CONFIGS_DIR, config, error) &&
                            scene::buildScene(config, built, error);
    std::filesystem::remove_all(dir); // the built scene holds the compiled grammar
    ASSERT_TRUE(builtScene) << error;
    const cells::BatchCatalog catalog(std::move(built));
    WalkComparison walks;
    compareWalks(catalog, 0, walks);
    ASSERT_GT(walks.compared, 200u);
    EXPECT_GT(walks.outcomes[size_t(Lod1Outcome::Terminal)], 0u);
    EXPECT_GT(walks.outcomes[size_t(Lod1Outcome::Stopped)], 0u);
    // Every wall is the same shape, so only a pixel on the limit's line may fall either side.
    EXPECT_GE(walks.agreed + 2, walks.compared) << walks.agreed << " of " << walks.compared;
}

} // namespace
} // namespace hexlod::lod
