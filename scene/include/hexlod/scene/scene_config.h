// The scene config: one JSON file that says what a city is made of (docs/scene.md).
// Parsing checks structure, types and ranges and names the offending field; names that
// need a compiled grammar (parameters) are checked when the scene is built.
#pragma once

#include "hexlod/scene/city_generator.h"

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace hexlod::scene {

using ParameterMap = std::map<std::string, double>;

struct GrammarEntry {
    std::string name;
    std::string path;    // resolved against the config file's folder
    ParameterMap params; // grammar-wide overrides
};

enum class BuildingSourceKind : uint8_t { Procedural, GeoJson, Osm };

struct BuildingSource {
    BuildingSourceKind kind = BuildingSourceKind::Procedural;
    std::string path;    // GeoJSON or OSM file, resolved
    std::string grammar; // GeoJSON and OSM: the grammar every imported building uses
    CityOptions city;    // procedural: the generator's options (trees from `trees`)
};

// Per-building overrides: building ids are those of the source's output, in source order.
struct BuildingOverride {
    uint32_t source = 0;
    std::vector<uint32_t> buildings;
    ParameterMap params;
};

struct TreeSpecies {
    std::string name;
    std::string grammar; // grammar name or file path, resolved
    ParameterMap params;
};

struct TreeConfig {
    uint32_t count = 0; // 0: no trees and no vegetation work at all
    std::vector<TreeSpecies> species;
};

// Where each terminal shape's mesh comes from; shapes not listed are procedural.
struct ShapeSource {
    std::string shape;
    std::string gltf; // resolved path of a .glb/.gltf mesh
};

struct LodProfile {
    double maxScreenSpaceError = 2.0; // pixels
    double hysteresis = 0.2;          // relative band around the terminal/extruded switch
    std::array<double, 5> geometricError{16.0, 4.0, 1.0, 0.25, 0.0}; // LOD0..LOD4, metres
    // A tree's billboard (one impostor per species, not per tree) against its own geometry:
    // trees are geometry while this error would show, billboards beyond.
    double treeGeometricError = 0.25;
};

struct CacheBudget {
    uint64_t memoryBytes = uint64_t(1) << 30;
    uint64_t diskBytes = uint64_t(4) << 30;
    std::string diskPath; // empty: no disk tier
};

struct SceneConfig {
    std::string name;
    std::string file; // the config's own path, for messages
    uint64_t seed = 1;
    double cellSize = 250.0;                     // hexagon circumradius, metres
    std::array<double, 3> origin{0.0, 0.0, 0.0}; // world metres added to every building, tree and street
    std::vector<GrammarEntry> grammars;
    std::vector<BuildingSource> sources;
    std::vector<BuildingOverride> overrides;
    TreeConfig trees;
    std::vector<ShapeSource> shapes;
    LodProfile lod;
    CacheBudget cache;

    int findGrammar(const std::string& grammarName) const;
};

// Parses `text`. Relative paths resolve against `baseDir`. On failure returns false with
// `error` as "<file>: <field.path>: <what is wrong>"; nothing is half-filled.
bool parseSceneConfig(std::string_view text, const std::string& file, const std::string& baseDir,
                      SceneConfig& out, std::string& error);
bool loadSceneConfig(const std::string& path, SceneConfig& out, std::string& error);

// Reads an LOD profile file (the scene config's "lod" object on its own, docs/scene.md) over
// the values already in `out`; false with "<file>: <field>: <problem>".
bool loadLodProfile(const std::string& path, LodProfile& out, std::string& error);

} // namespace hexlod::scene
