#include "hexlod/scene/scene_config_writer.h"

#include <filesystem>
#include <fstream>
#include <system_error>

namespace hexlod::scene {
namespace {

using Json = nlohmann::json;
namespace fs = std::filesystem;

std::string relativeTo(const std::string& path, const fs::path& base) {
    std::error_code ec;
    const fs::path absolute = fs::absolute(path, ec).lexically_normal();
    if (ec) return path;
    const fs::path relative = absolute.lexically_relative(base);
    return relative.empty() ? absolute.string() : relative.generic_string();
}

Json paramsJson(const ParameterMap& params) {
    Json out = Json::object();
    for (const auto& [name, value] : params) out[name] = value;
    return out;
}

Json sourceJson(const BuildingSource& source, const fs::path& base) {
    if (source.kind != BuildingSourceKind::Procedural)
        return {{"source", source.kind == BuildingSourceKind::Osm ? "osm" : "geojson"},
                {"path", relativeTo(source.path, base)},
                {"grammar", source.grammar}};
    const CityOptions& city = source.city;
    Json districts = Json::array();
    for (const DistrictSpec& d : city.districts)
        districts.push_back({{"grammar", d.grammar},
                             {"share", d.share},
                             {"floors", {d.minFloors, d.maxFloors}},
                             {"lot", {d.lotWidth, d.lotDepth}}});
    return {{"source", "procedural"},       {"count", city.buildings},
            {"block_size", city.blockSize}, {"street_width", city.streetWidth},
            {"park_share", city.parkShare}, {"districts", districts}};
}

} // namespace

Json sceneConfigToJson(const SceneConfig& config, const std::string& baseDir) {
    std::error_code ec;
    const fs::path base = fs::absolute(baseDir.empty() ? "." : baseDir, ec).lexically_normal();
    Json out;
    out["name"] = config.name;
    out["seed"] = config.seed;
    out["cell_size"] = config.cellSize;
    if (config.origin != std::array<double, 3>{0.0, 0.0, 0.0}) out["origin"] = config.origin;
    Json grammars = Json::object();
    for (const GrammarEntry& g : config.grammars) {
        Json entry = {{"file", relativeTo(g.path, base)}};
        if (!g.params.empty()) entry["params"] = paramsJson(g.params);
        grammars[g.name] = entry;
    }
    out["grammars"] = grammars;
    Json sources = Json::array();
    for (const BuildingSource& source : config.sources) sources.push_back(sourceJson(source, base));
    out["buildings"] = sources;
    if (!config.overrides.empty()) {
        Json overrides = Json::array();
        for (const BuildingOverride& o : config.overrides)
            overrides.push_back(
                {{"source", o.source}, {"buildings", o.buildings}, {"params", paramsJson(o.params)}});
        out["overrides"] = overrides;
    }
    if (config.trees.count > 0 || !config.trees.species.empty()) {
        Json species = Json::array();
        for (const TreeSpecies& s : config.trees.species) {
            Json entry = {{"name", s.name}, {"grammar", relativeTo(s.grammar, base)}};
            if (!s.params.empty()) entry["params"] = paramsJson(s.params);
            species.push_back(entry);
        }
        Json trees = {{"count", config.trees.count}};
        if (!species.empty()) trees["species"] = species;
        out["trees"] = trees;
    }
    if (!config.shapes.empty()) {
        Json shapes = Json::object();
        for (const ShapeSource& s : config.shapes) shapes[s.shape] = {{"gltf", relativeTo(s.gltf, base)}};
        out["shapes"] = shapes;
    }
    out["lod"] = {{"max_screen_space_error", config.lod.maxScreenSpaceError},
                  {"hysteresis", config.lod.hysteresis},
                  {"geometric_error", config.lod.geometricError},
                  {"tree_geometric_error", config.lod.treeGeometricError}};
    constexpr uint64_t kMiB = uint64_t(1) << 20;
    Json cache = {{"memory_mb", config.cache.memoryBytes / kMiB}, {"disk_mb", config.cache.diskBytes / kMiB}};
    if (!config.cache.diskPath.empty()) cache["disk_path"] = relativeTo(config.cache.diskPath, base);
    out["cache"] = cache;
    return out;
}

bool writeSceneConfig(const SceneConfig& config, const std::string& path, std::string& error) {
    const fs::path target(path);
    const fs::path folder = target.parent_path();
    const std::string text = sceneConfigToJson(config, folder.string()).dump(2) + "\n";
    const fs::path temporary = target.string() + ".tmp";
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        out << text;
        out.flush();
        if (!out) {
            error = "cannot write '" + temporary.string() + "'";
            return false;
        }
    }
    std::error_code ec;
    fs::rename(temporary, target, ec);
    if (ec) {
        fs::remove(temporary, ec);
        error = "cannot write '" + path + "': " + ec.message();
        return false;
    }
    return true;
}

} // namespace hexlod::scene
