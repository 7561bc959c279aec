#include "hexlod/scene/scene_config.h"

#include "json_fields.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

namespace hexlod::scene {
namespace {

std::string resolve(const std::string& baseDir, const std::string& path) {
    const std::filesystem::path p(path);
    return p.is_absolute() || baseDir.empty()
               ? path
               : (std::filesystem::path(baseDir) / p).lexically_normal().string();
}

std::string requiredPath(Fields& fields, const std::string& key, const std::string& baseDir) {
    const std::string path = fields.text(key, "");
    if (path.empty()) Fields::fail(fields.at(key), "is required");
    return resolve(baseDir, path);
}

ParameterMap readParams(const Json* value, const std::string& path) {
    ParameterMap params;
    if (!value) return params;
    if (!value->is_object()) Fields::fail(path, "expected an object of name: number");
    for (const auto& [name, number] : value->items()) {
        // Ranges come from the grammar and are checked when the scene is built.
        params[name] = Fields::checkedNumber(number, path + "." + name, -1e30, 1e30);
    }
    return params;
}

std::pair<double, double> readRange(Fields& fields, const std::string& key,
                                    std::pair<double, double> fallback, double hi) {
    const Json* value = fields.find(key);
    if (!value) return fallback;
    const std::string path = fields.at(key);
    if (!value->is_array() || value->size() != 2) Fields::fail(path, "expected [min, max]");
    const double lo = Fields::checkedNumber((*value)[0], path + "[0]", 0.0, hi);
    const double up = Fields::checkedNumber((*value)[1], path + "[1]", 0.0, hi);
    if (lo > up) Fields::fail(path, "min is greater than max");
    return {lo, up};
}

void readGrammars(Fields& root, const std::string& baseDir, SceneConfig& scene) {
    const Json& grammars = root.require("grammars");
    if (!grammars.is_object() || grammars.empty()) {
        Fields::fail("grammars", "expected an object of name: {\"file\": ...} with at least one grammar");
    }
    for (const auto& [name, value] : grammars.items()) {
        Fields fields(value, "grammars." + name);
        GrammarEntry entry;
        entry.name = name;
        entry.path = requiredPath(fields, "file", baseDir);
        entry.params = readParams(fields.find("params"), fields.at("params"));
        fields.finish();
        scene.grammars.push_back(std::move(entry));
    }
}

std::string grammarName(Fields& fields, const SceneConfig& scene) {
    const std::string name = fields.text("grammar", "");
    if (name.empty()) Fields::fail(fields.at("grammar"), "is required");
    if (scene.findGrammar(name) < 0)
        Fields::fail(fields.at("grammar"), "names no grammar in \"grammars\": '" + name + "'");
    return name;
}

CityOptions readCity(Fields& fields, const SceneConfig& scene, const std::string& path) {
    CityOptions city;
    city.seed = scene.seed;
    city.buildings = static_cast<uint32_t>(fields.whole("count", 10000, 10'000'000));
    city.blockSize = fields.number("block_size", city.blockSize, 20.0, 5000.0);
    city.streetWidth = fields.number("street_width", city.streetWidth, 2.0, 200.0);
    city.parkShare = fields.number("park_share", city.parkShare, 0.0, 0.9);
    const Json& districts = fields.require("districts");
    if (!districts.is_array() || districts.empty())
        Fields::fail(path + ".districts", "expected a non-empty array");
    for (size_t i = 0; i < districts.size(); ++i) {
        Fields d(districts[i], path + ".districts[" + std::to_string(i) + "]");
        DistrictSpec spec;
        spec.grammar = grammarName(d, scene);
        spec.share = d.number("share", 1.0, 1e-6, 1e6);
        const auto floors = readRange(d, "floors", {spec.minFloors, spec.maxFloors}, 1000.0);
        spec.minFloors = floors.first;
        spec.maxFloors = floors.second;
        const auto lot = readRange(d, "lot", {spec.lotWidth, spec.lotDepth}, 1000.0);
        if (lot.first < 4.0) Fields::fail(d.at("lot"), "lots must be at least 4 m wide");
        spec.lotWidth = lot.first;
        spec.lotDepth = lot.second;
        d.finish();
        city.districts.push_back(spec);
    }
    return city;
}

void readSources(Fields& root, const std::string& baseDir, SceneConfig& scene) {
    const Json& sources = root.require("buildings");
    if (!sources.is_array()) Fields::fail("buildings", "expected an array of building sources");
    for (size_t i = 0; i < sources.size(); ++i) {
        const std::string path = "buildings[" + std::to_string(i) + "]";
        Fields fields(sources[i], path);
        BuildingSource source;
        const std::string kind = fields.text("source", "");
        if (kind == "procedural") {
            source.kind = BuildingSourceKind::Procedural;
            source.city = readCity(fields, scene, path);
        } else if (kind == "geojson" || kind == "osm") {
            source.kind = kind == "osm" ? BuildingSourceKind::Osm : BuildingSourceKind::GeoJson;
            source.path = requiredPath(fields, "path", baseDir);
            source.grammar = grammarName(fields, scene);
        } else {
            Fields::fail(fields.at("source"), "expected \"procedural\", \"geojson\" or \"osm\"");
        }
        fields.finish();
        scene.sources.push_back(std::move(source));
    }
}

void readOverrides(Fields& root, SceneConfig& scene) {
    const Json* overrides = root.find("overrides");
    if (!overrides) return;
    if (!overrides->is_array()) Fields::fail("overrides", "expected an array");
    for (size_t i = 0; i < overrides->size(); ++i) {
        const std::string path = "overrides[" + std::to_string(i) + "]";
        Fields fields((*overrides)[i], path);
        BuildingOverride entry;
        entry.source = static_cast<uint32_t>(fields.whole("source", 0, 1'000'000));
        if (entry.source >= scene.sources.size())
            Fields::fail(fields.at("source"), "names no building source");
        const Json& ids = fields.require("buildings");
        if (!ids.is_array()) Fields::fail(fields.at("buildings"), "expected an array of building ids");
        for (size_t k = 0; k < ids.size(); ++k) {
            entry.buildings.push_back(static_cast<uint32_t>(Fields::checkedWhole(
                ids[k], fields.at("buildings") + "[" + std::to_string(k) + "]", 0xffffffffu)));
        }
        entry.params = readParams(&fields.require("params"), fields.at("params"));
        fields.finish();
        scene.overrides.push_back(std::move(entry));
    }
}

void readSpeciesList(const Json& list, const std::string& path, const std::string& baseDir,
                     TreeConfig& trees) {
    if (!list.is_array() || list.empty()) Fields::fail(path, "expected a non-empty array of species");
    for (size_t i = 0; i < list.size(); ++i) {
        Fields fields(list[i], path + "[" + std::to_string(i) + "]");
        TreeSpecies species;
        species.name = fields.text("name", "");
        if (species.name.empty()) Fields::fail(fields.at("name"), "is required");
        species.grammar = requiredPath(fields, "grammar", baseDir);
        species.params = readParams(fields.find("params"), fields.at("params"));
        fields.finish();
        trees.species.push_back(std::move(species));
    }
}

void readTrees(Fields& root, const std::string& baseDir, SceneConfig& scene) {
    const Json* value = root.find("trees");
    if (!value) return;
    Fields fields(*value, "trees");
    scene.trees.count = static_cast<uint32_t>(fields.whole("count", 0, 100'000'000));
    const Json* species = fields.find("species");
    if (species && species->is_string()) {
        // A species file: {"species": [...]}, with paths relative to that file.
        const std::string file = resolve(baseDir, species->get<std::string>());
        std::ifstream in(file);
        if (!in) Fields::fail("trees.species", "cannot open species file '" + file + "'");
        const Json document = Json::parse(in, nullptr, false);
        if (document.is_discarded() || !document.is_object() || !document.contains("species")) {
            Fields::fail("trees.species", "'" + file + "' is not a species file ({\"species\": [...]})");
        }
        readSpeciesList(document["species"], file + ": species",
                        std::filesystem::path(file).parent_path().string(), scene.trees);
    } else if (species) {
        readSpeciesList(*species, "trees.species", baseDir, scene.trees);
    }
    if (scene.trees.count > 0 && scene.trees.species.empty())
        Fields::fail("trees.species", "trees need species");
    fields.finish();
    for (BuildingSource& source : scene.sources) {
        if (source.kind != BuildingSourceKind::Procedural) continue;
        source.city.trees = scene.trees.count;
        source.city.species = static_cast<uint32_t>(std::max<size_t>(1, scene.trees.species.size()));
    }
}

void readShapes(Fields& root, const std::string& baseDir, SceneConfig& scene) {
    const Json* value = root.find("shapes");
    if (!value) return;
    if (!value->is_object()) Fields::fail("shapes", "expected an object of shape: {\"gltf\": path}");
    for (const auto& [shape, entry] : value->items()) {
        Fields fields(entry, "shapes." + shape);
        const std::string gltf = requiredPath(fields, "gltf", baseDir);
        fields.finish();
        scene.shapes.push_back({shape, gltf});
    }
}

void readLod(Fields& root, SceneConfig& scene) {
    if (const Json* value = root.find("lod")) scene.lod = readLodProfile(*value, "lod", scene.lod);
}

void readCache(Fields& root, const std::string& baseDir, SceneConfig& scene) {
    const Json* value = root.find("cache");
    if (!value) return;
    Fields fields(*value, "cache");
    constexpr uint64_t kMiB = uint64_t(1) << 20;
    scene.cache.memoryBytes = fields.whole("memory_mb", scene.cache.memoryBytes / kMiB, 1 << 24) * kMiB;
    scene.cache.diskBytes = fields.whole("disk_mb", scene.cache.diskBytes / kMiB, 1 << 26) * kMiB;
    const std::string disk = fields.text("disk_path", "");
    scene.cache.diskPath = disk.empty() ? "" : resolve(baseDir, disk);
    if (scene.cache.memoryBytes == 0) Fields::fail("cache.memory_mb", "must be at least 1");
    fields.finish();
}

} // namespace

int SceneConfig::findGrammar(const std::string& grammarName) const {
    for (size_t i = 0; i < grammars.size(); ++i) {
        if (grammars[i].name == grammarName) return static_cast<int>(i);
    }
    return -1;
}

bool parseSceneConfig(std::string_view text, const std::string& file, const std::string& baseDir,
                      SceneConfig& out, std::string& error) {
    Json document;
    if (!parseJsonText(text, file, document, error)) return false;
    SceneConfig scene;
    scene.file = file;
    try {
        Fields root(document, "");
        scene.name = root.text("name", std::filesystem::path(file).stem().string());
        scene.seed = root.whole("seed", 1, std::numeric_limits<int64_t>::max());
        scene.cellSize = root.number("cell_size", scene.cellSize, 1.0, 100000.0);
        if (const Json* origin = root.find("origin")) {
            if (!origin->is_array() || origin->size() != 3)
                Fields::fail("origin", "expected [x, y, z] in metres");
            for (size_t i = 0; i < 3; ++i)
                scene.origin[i] =
                    Fields::checkedNumber((*origin)[i], "origin[" + std::to_string(i) + "]", -1e9, 1e9);
        }
        readGrammars(root, baseDir, scene);
        readSources(root, baseDir, scene);
        readOverrides(root, scene);
        readTrees(root, baseDir, scene);
        readShapes(root, baseDir, scene);
        readLod(root, scene);
        readCache(root, baseDir, scene);
        root.finish();
    } catch (const ConfigError& e) {
        error = file + ": " + e.what();
        return false;
    }
    out = std::move(scene);
    return true;
}

bool loadSceneConfig(const std::string& path, SceneConfig& out, std::string& error) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        error = "cannot open scene config '" + path + "'";
        return false;
    }
    std::ostringstream text;
    text << in.rdbuf();
    return parseSceneConfig(text.str(), path, std::filesystem::path(path).parent_path().string(), out, error);
}

} // namespace hexlod::scene
