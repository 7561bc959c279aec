// The extreme-case suite's harness: one scene through the whole pipeline, as hexlod runs it:
// grammar expansion into the cell index's batches, the cache, the terminal-set payload a
// client receives (encoded and decoded back), the CPU reference of the cull and LOD pass for a
// camera, and a tiny GL frame of the same camera. Each case states what it expects of the
// result.
#pragma once

#include "hexlod/cache/terminal_set_cache.h"
#include "hexlod/cells/batch_catalog.h"
#include "hexlod/lod/cpu_cull.h"
#include "hexlod/render/image.h"
#include "hexlod/scene/camera_path.h"
#include "hexlod/scene/scene_builder.h"

#include <string>
#include <vector>

namespace hexlod::extreme {

// A scene of hand-made buildings of one grammar (grammar text or a configs/ path).
scene::BuiltScene sceneOf(const std::string& grammarSource, std::vector<grammar::BuildingInput> buildings,
                          double cellSize = 250.0);
grammar::BuildingInput building(uint32_t id, std::vector<glm::dvec2> footprint,
                                std::vector<float> parameters = {});
// Counter-clockwise w x d rectangle with its corner at `corner`.
std::vector<glm::dvec2> rectangle(double w, double d, glm::dvec2 corner = {0.0, 0.0});
scene::CameraPose lookAt(glm::dvec3 eye, glm::dvec3 target, double fovDegrees = 60.0);

struct PipelineResult {
    uint64_t terminals = 0;          // over every batch
    std::vector<std::string> issues; // expansion issues, formatted
    bool failedBatch = false;        // a batch-level cap was hit
    bool payloadsRoundTrip = true;   // every batch's encoded payload decodes to the same set
    uint64_t payloadBytes = 0;
    lod::CullResult cull;    // the CPU reference for the camera
    render::Image frame;     // empty when no GL frame was asked for
    bool glClean = true;     // no GL error reported while drawing it
    bool frameFinite = true; // every pixel finite
};

struct PipelineOptions {
    scene::CameraPose camera;
    bool render = true;
    uint32_t width = 96, height = 64;
    double nearPlane = 0.1, farPlane = 20000.0;
};

PipelineResult runPipeline(scene::BuiltScene scene, const PipelineOptions& options);

} // namespace hexlod::extreme
