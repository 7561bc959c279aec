// libFuzzer target for the scene config parser (docs/scene.md): arbitrary text must be refused
// with "<file>: <field>: <problem>" and nothing half-filled, or give a config whose numbers
// are finite and inside the ranges the rest of hexlod relies on. Relative paths resolve
// against the shipped configs folder, so grammar and species references can be real.
#include "fuzz_check.h"

#include "hexlod/scene/scene_config.h"

using hexlod::fuzz::allFinite;
using hexlod::fuzz::check;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    hexlod::scene::SceneConfig config;
    std::string error;
    if (!hexlod::scene::parseSceneConfig(text, "fuzz.json", HEXLOD_CONFIGS_DIR, config, error)) {
        check(hexlod::fuzz::startsWith(error, "fuzz.json:") &&
              error.size() > 11); // ": field: " or ":line:col: "
        check(config.grammars.empty() && config.sources.empty() &&
              config.name.empty()); // nothing half-filled
        return 0;
    }
    check(error.empty());
    check(allFinite(config.cellSize) && config.cellSize > 0.0);
    check(allFinite(config.origin[0], config.origin[1], config.origin[2]));
    for (const hexlod::scene::BuildingOverride& o : config.overrides) check(o.source < config.sources.size());
    const hexlod::scene::LodProfile& lod = config.lod;
    check(allFinite(lod.maxScreenSpaceError, lod.hysteresis) && lod.maxScreenSpaceError > 0.0);
    check(lod.hysteresis >= 0.0 && lod.hysteresis <= 0.95);
    for (const double e : lod.geometricError) check(allFinite(e) && e >= 0.0);
    check(allFinite(lod.treeGeometricError) && lod.treeGeometricError >= 0.0);
    return 0;
}
