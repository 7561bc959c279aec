// `hexlod export --scene S --journal J -o scene.json` as a library call: the scene with every
// journal edit applied, written as a scene config of its own (docs/scene.md) that loads back
// to the same parameters. Edits become per-building overrides (scene_config.h
// BuildingOverride), grouped so that a building keeps the config overrides it had and
// buildings with the same values share one entry; tree edits become species parameters.
#pragma once

#include "hexlod/cells/batch_catalog.h"
#include "hexlod/scene/scene_config.h"

#include <string>
#include <vector>

namespace hexlod::server {

struct ExportReport {
    size_t entries = 0;             // journal entries read
    size_t editedBuildings = 0;     // buildings whose parameters differ from the config's
    size_t overrides = 0;           // override entries added
    size_t editedSpecies = 0;       // tree species whose parameters changed
    std::vector<std::string> notes; // journal notes (torn tail, skipped entries)
};

// `original` config, `baseline` its scene as built without edits, `edited` the catalog with
// the edits applied. False with `error` when an edit cannot be expressed in a config (trees
// of one species edited apart: a config sets tree parameters per species only).
bool editedSceneConfig(const scene::SceneConfig& original, const scene::BuiltScene& baseline,
                       const cells::BatchCatalog& edited, scene::SceneConfig& out, ExportReport& report,
                       std::string& error);

// Builds the scene, replays the journal read-only (nothing is truncated or rewritten) and
// writes the edited config to `outPath`.
bool exportEditedScene(const scene::SceneConfig& config, const std::string& journalPath,
                       const std::string& outPath, ExportReport& report, std::string& error);

} // namespace hexlod::server
