#include "pipeline.h"

#include "hexlod/grammar/terminal_set_codec.h"
#include "hexlod/lod/city_renderer.h"
#include "hexlod/render/gl_context.h"
#include "hexlod/render/gl_debug.h"
#include "hexlod/render/terminal_mesh_library.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace hexlod::extreme {

std::vector<glm::dvec2> rectangle(double w, double d, glm::dvec2 corner) {
    return {corner, corner + glm::dvec2(w, 0.0), corner + glm::dvec2(w, d), corner + glm::dvec2(0.0, d)};
}

grammar::BuildingInput building(uint32_t id, std::vector<glm::dvec2> footprint,
                                std::vector<float> parameters) {
    grammar::BuildingInput b;
    b.id = id;
    b.footprint = std::move(footprint);
    b.parameters = std::move(parameters);
    return b;
}

scene::CameraPose lookAt(glm::dvec3 eye, glm::dvec3 target, double fovDegrees) {
    scene::CameraPose pose;
    pose.position = eye;
    pose.forward = glm::normalize(target - eye);
    pose.up = glm::dvec3(0, 0, 1); // the renderer rebuilds it when it is unusable
    pose.fovY = fovDegrees * 3.14159265358979323846 / 180.0;
    return pose;
}

scene::BuiltScene sceneOf(const std::string& grammarSource, std::vector<grammar::BuildingInput> buildings,
                          double cellSize) {
    scene::BuiltScene scene;
    scene.config.name = "extreme";
    scene.config.cellSize = cellSize;
    scene::GrammarBuildings grammar;
    grammar.name = "g";
    grammar::DiagnosticList diagnostics;
    grammar.grammar =
        grammarSource.find("->") == std::string::npos
            ? grammar::compileGrammarFile(std::string(HEXLOD_CONFIGS_DIR) + "/" + grammarSource, diagnostics)
            : grammar::compileGrammar(grammarSource, "extreme.grammar", diagnostics);
    EXPECT_FALSE(diagnostics.hasErrors()) << diagnostics.formatAll();
    for (grammar::BuildingInput& b : buildings)
        if (b.parameters.empty()) b.parameters = grammar.grammar.defaultParameters();
    grammar.buildings = std::move(buildings);
    scene.config.grammars.push_back({"g", grammarSource, {}});
    scene.buildingGrammars.push_back(std::move(grammar));
    return scene;
}

PipelineResult runPipeline(scene::BuiltScene scene, const PipelineOptions& options) {
    PipelineResult result;
    cells::BatchCatalog catalog(std::move(scene));
    cache::TerminalSetCache cache(cache::CacheOptions{});
    lod::CullInputs inputs;
    std::vector<std::shared_ptr<const grammar::TerminalSet>> sets;
    for (uint32_t b = 0; b < catalog.batchCount(); ++b) {
        grammar::BatchResult expanded = catalog.expand(b);
        result.failedBatch |= expanded.failed;
        for (const grammar::BatchIssue& issue : expanded.issues)
            result.issues.push_back(grammar::describeIssue(catalog.grammar(catalog.batch(b).grammar).grammar,
                                                           issue.first, issue.occurrences));
        result.terminals += expanded.terminals.records.size();
        // The payload a client receives: encoded, then decoded back to the same records.
        const std::vector<uint8_t> payload = grammar::encodeTerminalSet(expanded.terminals);
        result.payloadBytes += payload.size();
        grammar::TerminalSet decoded;
        std::string error;
        if (!grammar::decodeTerminalSet(payload, decoded, error) ||
            decoded.records.size() != expanded.terminals.records.size() ||
            (!decoded.records.empty() &&
             std::memcmp(decoded.records.data(), expanded.terminals.records.data(),
                         decoded.records.size() * sizeof(grammar::TerminalRecord)) != 0)) {
            result.payloadsRoundTrip = false;
        }
        cache.insert(catalog.key(b), std::move(expanded.terminals));
        sets.push_back(catalog.fetch(b, cache));
    }
    // The CPU reference of the cull and LOD pass for the camera, every batch resident.
    const scene::CameraPose pose = scene::usablePose(options.camera);
    const double aspect = double(options.width) / double(options.height);
    inputs.camera = pose.position;
    uint32_t shapeBase = 0;
    std::vector<uint32_t> bases;
    for (uint32_t g = 0; g < catalog.index().grammarCount(); ++g) {
        bases.push_back(shapeBase);
        shapeBase += uint32_t(catalog.grammar(g).grammar.shapes.size());
    }
    inputs.shapeCount = shapeBase;
    inputs.shapeImpostor.assign(shapeBase, 1);
    for (uint32_t b = 0; b < catalog.batchCount(); ++b)
        inputs.batches.push_back({sets[b].get(), nullptr, catalog.cellOrigin(catalog.batch(b).cell),
                                  bases[catalog.batch(b).grammar]});
    try {
        const cells::Frustum frustum(pose.position, pose.forward, pose.up, pose.fovY, aspect,
                                     options.nearPlane, options.farPlane);
        inputs.frame =
            lod::makeCullFrame(frustum, catalog.scene().config.lod, pose.fovY, options.height, 0.15, true);
        result.cull = lod::cullOnCpu(inputs);
    } catch (const std::invalid_argument& e) {
        ADD_FAILURE() << "the frustum refused the camera: " << e.what();
    }
    if (!options.render) return result;

    render::GlContextResult gl = render::createGlContext();
    if (!gl.context) {
        ADD_FAILURE() << gl.error();
        return result;
    }
    const uint64_t errorsBefore = render::glDebugErrorCount();
    std::vector<const grammar::CompiledGrammar*> grammars;
    for (uint32_t g = 0; g < catalog.index().grammarCount(); ++g)
        grammars.push_back(&catalog.grammar(g).grammar);
    const render::TerminalMeshLibrary meshes(grammars);
    lod::CityRendererOptions renderOptions;
    renderOptions.width = options.width;
    renderOptions.height = options.height;
    renderOptions.mode = lod::RenderMode::AllLod4;
    renderOptions.arenaRecords = 1 << 20;
    lod::CityRenderer renderer(catalog, cache, meshes, nullptr, renderOptions);
    std::string error;
    if (!renderer.init(error)) {
        ADD_FAILURE() << error;
        return result;
    }
    renderer.render(pose, 0.0, options.nearPlane, options.farPlane);
    result.frame = renderer.readColor();
    result.glClean = render::glDebugErrorCount() == errorsBefore;
    for (float v : result.frame.pixels) result.frameFinite &= std::isfinite(v);
    return result;
}

} // namespace hexlod::extreme
