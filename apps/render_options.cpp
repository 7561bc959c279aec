#include "render_options.h"

namespace hexlod::apps {

void addRenderOptions(CLI::App& command, RenderOptions& o) {
    command.add_option("--width", o.width, "Target width in pixels (default: the camera path's viewport)");
    command.add_option("--height", o.height, "Target height in pixels");
    command.add_option("--gl", o.backend, "GL backend: auto, egl-device, egl-surfaceless, osmesa");
    command.add_option("--impostor-grid", o.impostorGrid, "Impostor views per side (2 to 32)");
    command.add_option("--impostor-res", o.impostorResolution, "Texels per impostor view side");
    command.add_option("--impostor-cache", o.impostorStore,
                       "Folder of baked impostors (EXR), reused across runs");
    command.add_option("--workers", o.workers,
                       "Background generation threads (0: visible batches in the frame, deterministic, "
                       "and the prefetch on an idle-priority thread)");
    command.add_option("--samples", o.samples, "Samples per pixel (multisampling; 1 to the GL's maximum)");
}

bool makeRenderSetup(const RenderOptions& o, RenderSetup& setup, std::string& error) {
    if (!render::parseGlBackend(o.backend, setup.backend)) {
        error = "--gl: unknown backend '" + o.backend + "' (auto, egl-device, egl-surfaceless, osmesa)";
        return false;
    }
    if (o.impostorGrid < impostor::kMinGrid || o.impostorGrid > impostor::kMaxGrid) {
        error = "--impostor-grid: " + std::to_string(o.impostorGrid) + " is outside [2, 32]";
        return false;
    }
    if (o.impostorResolution < 16 || o.impostorResolution > 1024) {
        error = "--impostor-res: " + std::to_string(o.impostorResolution) + " is outside [16, 1024]";
        return false;
    }
    if ((o.width == 0) != (o.height == 0) || o.width > 16384 || o.height > 16384) {
        error = "--width and --height: give both, each in [1, 16384]";
        return false;
    }
    if (o.samples == 0 || o.samples > 64) {
        error = "--samples: " + std::to_string(o.samples) + " is outside [1, 64]";
        return false;
    }
    setup.impostorGrid = o.impostorGrid;
    setup.impostorResolution = o.impostorResolution;
    setup.impostorStore = o.impostorStore;
    setup.samples = o.samples;
    return true;
}

glm::dvec3 sceneCentre(const cells::BatchCatalog& catalog) {
    glm::dvec2 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (const cells::CellBounds& cell : catalog.index().cells()) {
        lo = glm::min(lo, cell.lo);
        hi = glm::max(hi, cell.hi);
    }
    if (lo.x > hi.x) return glm::dvec3(0.0);
    return glm::dvec3(0.5 * (lo + hi), 0.0);
}

} // namespace hexlod::apps
