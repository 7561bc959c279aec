// SceneService: the JSON views (docs/protocol.md): scene summary, cell index, one building,
// the edit history and the event stream's hello.
#include "hexlod/server/scene_service.h"

#include "hexlod/grammar/extruded_set_codec.h"
#include "hexlod/grammar/terminal_set_codec.h"
#include "hexlod/server/http_types.h"

#include <charconv>
#include <cstdlib>
#include <filesystem>

namespace hexlod::server {
namespace {

using Json = nlohmann::json;

const char* statusName(int status) {
    return status == 0 ? "applied" : status == 1 ? "undone" : "skipped";
}

// Parameters are floats: printed as the shortest decimal that reads back to the same float
// (3.8, not 3.799999952316284), which an edit then turns into that very float again.
double decimal(float value) {
    char text[32];
    const auto result = std::to_chars(text, text + sizeof(text), value);
    return std::strtod(std::string(text, result.ptr).c_str(), nullptr);
}

Json parameterJson(const grammar::ParameterInfo& p) {
    return {{"name", p.name},
            {"default", decimal(p.defaultValue)},
            {"min", decimal(p.minValue)},
            {"max", decimal(p.maxValue)}};
}

Json vec3Json(const std::array<float, 3>& v) {
    return {decimal(v[0]), decimal(v[1]), decimal(v[2])};
}

// An impostor's files and sphere; `url(suffix)` names its files.
template <typename UrlOf> Json impostorJson(const ImpostorAsset& impostor, const UrlOf& url) {
    return {{"albedo_url", url(".albedo.png")},
            {"normal_url", url(".normal.png")},
            {"exr_url", impostor.exr ? Json(url(".exr")) : Json(nullptr)},
            {"centre", vec3Json(impostor.centre)},
            {"radius", decimal(impostor.radius)},
            {"bounds_min", vec3Json(impostor.boundsMin)},
            {"bounds_max", vec3Json(impostor.boundsMax)},
            {"layer", impostor.layer}};
}

std::string speciesUrl(uint32_t species, uint64_t key, const char* suffix) {
    return "/api/v1/tree-impostors/" + std::to_string(species) + "/" + cache::hexDigest(key) + suffix;
}

// "/api/v1/{collection}/{grammar}/{shape}/{key}" + suffix: every shape asset's URL.
std::string shapeAssetUrl(const char* collection, uint32_t grammar, uint32_t shape, uint64_t key,
                          const char* suffix) {
    return std::string("/api/v1/") + collection + "/" + std::to_string(grammar) + "/" +
           std::to_string(shape) + "/" + cache::hexDigest(key) + suffix;
}

} // namespace

std::string SceneService::meshUrl(uint32_t grammar, uint32_t shape) const {
    const MeshAsset* mesh = assets_.mesh(grammar, shape);
    return mesh ? shapeAssetUrl("meshes", grammar, shape, mesh->hash, ".glb") : std::string();
}

std::string SceneService::coarseMeshUrl(uint32_t grammar, uint32_t shape) const {
    const MeshAsset* mesh = assets_.mesh(grammar, shape);
    return mesh && mesh->coarse ? shapeAssetUrl("meshes", grammar, shape, mesh->coarse->hash, ".coarse.glb")
                                : std::string();
}

std::string SceneService::impostorUrl(uint32_t grammar, uint32_t shape, const char* suffix) const {
    const ImpostorAsset* impostor = assets_.impostor(grammar, shape);
    return impostor ? shapeAssetUrl("impostors", grammar, shape, impostor->key, suffix) : std::string();
}

// A declared shape: its declaration, and the URLs of its mesh and impostor where served.
Json SceneService::shapeJson(uint32_t grammar, uint32_t shape) const {
    const grammar::ShapeInfo& s = catalog_->grammar(grammar).grammar.shapes[shape];
    Json out = {{"id", shape},
                {"index", shape},
                {"name", s.name},
                {"width", decimal(s.width)},
                {"height", decimal(s.height)},
                {"depth", decimal(s.depth)},
                {"depth_ratio", decimal(s.depthRatio)},
                {"triangles", s.triangles}};
    const MeshAsset* mesh = assets_.mesh(grammar, shape);
    out["nominal_size"] =
        mesh ? vec3Json(mesh->nominalSize)
             : Json{decimal(s.width), decimal(s.height), decimal(s.depthRatio * std::min(s.width, s.height))};
    out["mesh_url"] = mesh ? Json(meshUrl(grammar, shape)) : Json(nullptr);
    out["coarse_mesh"] = nullptr;
    if (mesh && mesh->coarse)
        out["coarse_mesh"] = {{"url", coarseMeshUrl(grammar, shape)},
                              {"deviation", vec3Json(mesh->coarse->deviation)},
                              {"triangles", mesh->coarse->triangles}};
    const ImpostorAsset* impostor = assets_.impostor(grammar, shape);
    if (!impostor) {
        out["impostor"] = nullptr;
        return out;
    }
    out["impostor"] =
        impostorJson(*impostor, [&](const char* suffix) { return impostorUrl(grammar, shape, suffix); });
    return out;
}

std::string SceneService::speciesImpostorUrl(uint32_t species, const char* suffix) const {
    const std::optional<SpeciesAsset> asset = this->species(species);
    if (!asset) return {};
    return speciesUrl(species, asset->impostor.key, suffix);
}

// One species as /api/v1/scene lists it and its event announces it.
Json SceneService::speciesEntryJson(uint32_t index) const {
    const SpeciesAsset& species = species_[index];
    Json parameters = Json::array();
    for (const float value : species.parameters) parameters.push_back(decimal(value));
    return {{"index", index},
            {"name", species.name},
            {"grammar", species.grammar},
            {"parameters", parameters},
            {"impostor", impostorJson(species.impostor, [&](const char* suffix) {
                 return speciesUrl(index, species.impostor.key, suffix);
             })}};
}

// The species whose billboards the service serves, in the order of their impostors' layers.
Json SceneService::speciesJson() const {
    Json out = Json::array();
    for (uint32_t s = 0; s < species_.size(); ++s)
        if (!species_[s].retired) out.push_back(speciesEntryJson(s));
    return out;
}

void SceneService::attachShapeAssets(ShapeAssets assets) {
    assets_ = std::move(assets);
    assetsAttached_ = true;
    {
        std::lock_guard lock(speciesMutex_);
        species_ = std::move(assets_.species); // from here on the service's, and growing
        assets_.species.clear();
        startSpecies_ = species_.size();
        for (const SpeciesAsset& s : species_)
            speciesStates_[{s.grammar, s.parameters}] = SpeciesState::Served;
    }
    staticSummary_ = staticSummary();
}

Json SceneService::staticSummary() const {
    const cells::BatchCatalog& catalog = *catalog_;
    const scene::BuiltScene& scene = catalog.scene();
    const cells::CellIndex& index = catalog.index();
    Json grammars = Json::array();
    for (uint32_t g = 0; g < index.grammarCount(); ++g) {
        const scene::GrammarBuildings& gb = catalog.grammar(g);
        Json params = Json::array(), shapes = Json::array();
        for (const grammar::ParameterInfo& p : gb.grammar.params) params.push_back(parameterJson(p));
        for (uint32_t s = 0; s < gb.grammar.shapes.size(); ++s) shapes.push_back(shapeJson(g, s));
        size_t batches = 0;
        for (const cells::Batch& b : index.batches()) batches += b.grammar == g;
        grammars.push_back({{"index", g},
                            {"name", gb.name},
                            {"label", std::filesystem::path(gb.name).stem().string()},
                            {"kind", index.isTreeGrammar(g) ? "tree" : "building"},
                            {"members", gb.buildings.size()},
                            {"batches", batches},
                            {"content_hash", cache::hexDigest(gb.grammar.contentHash)},
                            {"parameters", params},
                            {"shapes", shapes}});
    }
    const scene::LodProfile& lod = scene.config.lod;
    return {
        {"name", scene.config.name},
        {"seed", scene.config.seed},
        {"cell_size", scene.config.cellSize},
        {"grid",
         {{"orientation", "pointy-top"},
          {"coordinates", "axial (q, r)"},
          {"size", scene.config.cellSize},
          {"origin", {0.0, 0.0}}}},
        {"coordinates",
         "world metres, x east, y north, z up; content positions are relative to their cell's origin"},
        {"counts",
         {{"buildings", index.buildingCount()},
          {"trees", index.treeCount()},
          {"cells", index.cells().size()},
          {"batches", catalog.batchCount()}}},
        {"grammars", grammars},
        {"lod",
         {{"max_screen_space_error", lod.maxScreenSpaceError},
          {"hysteresis", lod.hysteresis},
          {"geometric_error", lod.geometricError},
          {"tree_geometric_error", lod.treeGeometricError},
          {"policy",
           "per cell: sse = geometric_error[1] * viewport_height / (distance * 2 * tan(fov_y / 2)), "
           "distance from the camera to the cell's bounds box; a cell switches to terminal sets above "
           "max_screen_space_error * (1 + hysteresis) and back to its extruded set below "
           "max_screen_space_error * (1 - hysteresis); per tree, the same formula with "
           "tree_geometric_error and the distance to the tree: terminals above "
           "max_screen_space_error, its species' billboard at or below it (0: terminals in terminal-set "
           "cells at any distance)"}}},
        {"attributions", scene.attributions},
        {"impostor_layout", assets_.impostorLayout},
        {"tree_species", nullptr}, // summary() fills it: edits add species
        {"tree_impostor_layout", assets_.speciesLayout},
        {"formats",
         {{"terminal_set", grammar::kTerminalSetFormatVersion},
          {"extruded_set", grammar::kExtrudedSetFormatVersion}}},
        {"capabilities",
         {{"terminal_sets", true},
          {"extruded_sets", true},
          {"terminal_meshes", assets_.meshesServed},
          {"impostors", assets_.impostorsServed},
          {"tree_billboards", assets_.speciesServed},
          {"edits", true},
          {"undo", true},
          {"events", true},
          {"edit_auth", options_.editsNeedToken ? "bearer" : "none"}}},
        {"endpoints",
         {{"cells", "/api/v1/cells"},
          {"terminal_set", "/api/v1/terminal-sets/{q},{r}/{grammar}/{key}"},
          {"extruded_set", "/api/v1/extruded-sets/{q},{r}/{grammar}/{key}"},
          {"building", "/api/v1/buildings/{id}"},
          {"terminal_mesh", "/api/v1/meshes/{grammar}/{shape}/{hash}.glb"},
          {"impostor", "/api/v1/impostors/{grammar}/{shape}/{key}.{albedo.png|normal.png|exr}"},
          {"tree_impostor", "/api/v1/tree-impostors/{species}/{key}.{albedo.png|normal.png|exr}"},
          {"edits", "/api/v1/edits"},
          {"undo", "/api/v1/edits/undo"},
          {"events", "/api/v1/events"},
          {"metrics", "/metrics"},
          {"health", "/healthz"}}},
    };
}

Json SceneService::summary() const {
    Json out = staticSummary_;
    out["notes"] = notes_;
    if (assetsAttached_) {
        for (const std::string& note : assets_.notes) out["notes"].push_back(note);
    } else {
        out["notes"].push_back("terminal meshes (glTF): not served by this service (none attached)");
        out["notes"].push_back("impostors (EXR, PNG): not served by this service (none attached)");
    }
    {
        std::shared_lock lock(catalogMutex_);
        size_t edits = 0, undos = 0;
        for (const HistoryRecord& r : history_) ++(r.entry.op == JournalEntry::Op::Edit ? edits : undos);
        out["journal"] = {{"entries", history_.size()},
                          {"edits", edits},
                          {"undos", undos},
                          {"undo_available", !undoStack_.empty()}};
    }
    {
        std::lock_guard lock(speciesMutex_);
        out["tree_species"] = speciesJson();
    }
    out["edits"] = out["journal"]["entries"];
    out["index_etag"] = stateEtag();
    out["seq"] = lastSeq();
    return out;
}

std::string SceneService::buildIndex() const {
    const cells::BatchCatalog& catalog = *catalog_;
    const cells::CellIndex& index = catalog.index();
    Json cellList = Json::array();
    for (const cells::CellBounds& cell : index.cells()) {
        const glm::dvec3 origin = catalog.cellOrigin(cell.cell);
        Json batches = Json::array();
        size_t buildings = 0, trees = 0;
        for (const cells::Batch& b : index.batchesOf(cell.cell)) {
            const uint32_t id = static_cast<uint32_t>(&b - index.batches().data());
            const BatchState& state = state_[id];
            (index.isTreeGrammar(b.grammar) ? trees : buildings) += b.buildings.size();
            batches.push_back({{"grammar", b.grammar},
                               {"members", b.buildings.size()},
                               {"key", state.key.hex()},
                               {"version", state.version},
                               {"terminal_set", contentUrl(PayloadKind::TerminalSet, id, state.key)},
                               {"extruded_set", contentUrl(PayloadKind::ExtrudedSet, id, state.key)}});
        }
        cellList.push_back(
            {{"q", cell.cell.q},
             {"r", cell.cell.r},
             {"origin", {origin.x, origin.y, origin.z}},
             {"bounds",
              {{"min", {cell.lo.x, cell.lo.y, cell.zMin}}, {"max", {cell.hi.x, cell.hi.y, cell.zMax}}}},
             {"buildings", buildings},
             {"trees", trees},
             {"batches", batches}});
    }
    return jsonText(
        Json{{"seq", lastSeq_}, {"cell_size", catalog.scene().config.cellSize}, {"cells", cellList}});
}

SceneService::IndexView SceneService::cellIndex() {
    std::lock_guard build(indexMutex_);
    std::shared_lock lock(stateMutex_);
    if (!indexJson_ || indexBuiltFor_ != lastSeq_) {
        indexJson_ = std::make_shared<const std::string>(buildIndex());
        indexBuiltFor_ = lastSeq_;
    }
    return {indexJson_, "W/\"" + std::to_string(lastSeq_) + "-" + cache::hexDigest(stateDigest_) + "\""};
}

std::optional<Json> SceneService::building(uint32_t id) const {
    if (id >= buildingRefs_.size()) return std::nullopt;
    const cells::BuildingRef ref = buildingRefs_[id];
    std::shared_lock lock(catalogMutex_);
    const cells::BatchCatalog& catalog = *catalog_;
    const scene::GrammarBuildings& gb = catalog.grammar(ref.grammar);
    const grammar::BuildingInput& input = gb.buildings[ref.building];
    const std::vector<float> values =
        input.parameters.empty() ? gb.grammar.defaultParameters() : input.parameters;
    Json params = Json::object();
    for (size_t p = 0; p < gb.grammar.params.size() && p < values.size(); ++p)
        params[gb.grammar.params[p].name] = decimal(values[p]);
    const cells::HexCoord cell = catalog.index().cellOfBuilding(ref.grammar, ref.building);
    const uint32_t batch = *findBatch(cell, ref.grammar);
    const BatchState state = batchState(batch);
    const scene::BuildingOrigin origin = catalog.scene().buildingOrigins[id];
    return Json{{"id", id},
                {"grammar", ref.grammar},
                {"grammar_name", gb.name},
                {"cell", {cell.q, cell.r}},
                {"source", {{"index", origin.source}, {"id", origin.sourceId}}},
                {"base_elevation", input.baseElevation},
                {"footprint_vertices", input.footprint.size()},
                {"params", params},
                {"batch",
                 {{"key", state.key.hex()},
                  {"version", state.version},
                  {"terminal_set", contentUrl(PayloadKind::TerminalSet, batch, state.key)},
                  {"extruded_set", contentUrl(PayloadKind::ExtrudedSet, batch, state.key)}}}};
}

Json SceneService::history(uint64_t since, size_t limit) const {
    std::shared_lock lock(catalogMutex_);
    Json entries = Json::array();
    for (const HistoryRecord& r : history_) {
        if (r.entry.seq <= since) continue;
        if (entries.size() >= limit) break;
        Json e = {{"seq", r.entry.seq},
                  {"op", r.entry.op == JournalEntry::Op::Edit ? "edit" : "undo"},
                  {"time", r.entry.time},
                  {"status", statusName(static_cast<int>(r.status))},
                  {"changed_batches", r.changed}};
        if (r.entry.op == JournalEntry::Op::Edit) {
            e["selector"] = r.entry.selector;
            e["params"] = r.entry.params;
            if (!r.entry.comment.empty()) e["comment"] = r.entry.comment;
        } else {
            e["undoes"] = r.entry.undoes;
        }
        if (!r.reason.empty()) e["reason"] = r.reason;
        if (r.undoneBy) e["undone_by"] = r.undoneBy;
        entries.push_back(std::move(e));
    }
    const Json next = undoStack_.empty() ? Json(nullptr) : Json(history_[undoStack_.back()].entry.seq);
    return {{"entries", entries}, {"total", history_.size()}, {"undo_next", next}};
}

Json SceneService::hello() const {
    // A client that missed a "species" event (they are not replayed) sees the count grow.
    return {{"seq", lastSeq()}, {"index_etag", stateEtag()}, {"tree_species", speciesCount()}};
}

} // namespace hexlod::server
