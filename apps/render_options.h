// Options every rendering command takes (walk, bench error, bake): target size, GL backend,
// impostor layout and store, scheduling.
#pragma once

#include "city_session.h"
#include "hexlod/lod/city_renderer.h"

#include <CLI/CLI.hpp>

#include <string>

namespace hexlod::apps {

struct RenderOptions {
    uint32_t width = 0, height = 0; // 0: the camera path's viewport
    std::string backend = "auto";
    uint32_t impostorGrid = 8, impostorResolution = 32;
    std::string impostorStore;
    uint32_t workers = 0;
    uint32_t samples = 1; // multisampling
};

void addRenderOptions(CLI::App& command, RenderOptions& options);
// Validates the options into a RenderSetup; false with a message naming the option.
bool makeRenderSetup(const RenderOptions& options, RenderSetup& setup, std::string& error);
// The scene's centre at ground level, the origin of paths "relative_to": "scene_centre".
glm::dvec3 sceneCentre(const cells::BatchCatalog& catalog);

} // namespace hexlod::apps
