// Writes a scene config back as the JSON that docs/scene.md describes, so that loading the
// file gives the same SceneConfig: the inverse of parseSceneConfig. `hexlod export` uses it
// to save a scene with its edits applied as overrides.
#pragma once

#include "hexlod/scene/scene_config.h"

#include <nlohmann/json.hpp>

#include <string>

namespace hexlod::scene {

// Paths (grammars, imported files, species grammars, shape meshes, the disk cache) are
// written relative to `baseDir`, the folder the file will live in; a path on another root
// stays absolute. Tree species are written inline.
nlohmann::json sceneConfigToJson(const SceneConfig& config, const std::string& baseDir);

// Writes the config to `path` through a temporary file and a rename, so a failed write leaves
// no half file. Returns false with `error` naming the path.
bool writeSceneConfig(const SceneConfig& config, const std::string& path, std::string& error);

} // namespace hexlod::scene
