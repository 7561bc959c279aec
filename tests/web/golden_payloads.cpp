// Writes what the viewer's JavaScript decoders are tested against (ctest web.golden_payloads,
// then web.decoders): real terminal-set and extruded-set payloads of residential and business
// batches, encoded by the C++ codecs, each with a JSON file of what the C++ decoder reads from
// it; and the impostor view layout (directions, view frames, tile origins, the table of views and
// weights the GPU blends) the viewer's impostor shader code must reproduce.
//   web_golden_payloads OUTPUT_FOLDER
#include "hexlod/grammar/batch_expander.h"
#include "hexlod/grammar/extruded_set_codec.h"
#include "hexlod/grammar/terminal_set_codec.h"
#include "hexlod/impostor/view_layout.h"
#include "hexlod/impostor/view_lookup.h"
#include "hexlod/scene/demo_footprints.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

namespace {

using Json = nlohmann::json;
using namespace hexlod;

std::string hex(uint64_t v) {
    char text[17];
    std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(v));
    return text;
}

Json vec(const glm::vec3& v) {
    return Json::array({v.x, v.y, v.z});
}

void write(const std::filesystem::path& path, const std::vector<uint8_t>& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!out) throw std::runtime_error("cannot write " + path.string());
}

void write(const std::filesystem::path& path, const Json& json) {
    std::ofstream out(path);
    out << json.dump(1) << "\n";
    if (!out) throw std::runtime_error("cannot write " + path.string());
}

grammar::BatchResult expand(const std::string& grammarName, uint32_t buildings, uint64_t seed) {
    grammar::DiagnosticList diagnostics;
    static std::vector<std::unique_ptr<grammar::CompiledGrammar>> grammars; // outlive the results
    grammars.push_back(std::make_unique<grammar::CompiledGrammar>(grammar::compileGrammarFile(
        std::string(HEXLOD_CONFIGS_DIR) + "/grammars/" + grammarName + ".grammar", diagnostics)));
    if (diagnostics.hasErrors()) throw std::runtime_error(diagnostics.formatAll());
    const grammar::CompiledGrammar& g = *grammars.back();
    std::vector<grammar::BuildingInput> input = scene::makeDemoFootprints({buildings, seed, 60.0});
    for (grammar::BuildingInput& b : input)
        b.parameters =
            grammar::resolveParameters(g, scene::demoParameterOverrides(g, seed, b.id), diagnostics);
    grammar::BatchInput batch;
    batch.grammar = &g;
    batch.buildings = input;
    batch.settings.seed = seed;
    // Far from the world origin, so the doubles of the header are tested beyond float range.
    batch.settings.cellOrigin = {6378137.25, -1234567.5, 12.0};
    batch.cell = {-7, 11};
    batch.grammarIndex = 1;
    grammar::BatchResult result = expandBatch(batch);
    result.terminals.header.key = 0x0123456789abcdefull + seed;
    return result;
}

// What decodeTerminalSet reads, with every record unpacked as unpackTerminal does.
Json terminalExpectation(const std::vector<uint8_t>& payload) {
    grammar::TerminalSet set;
    std::string error;
    if (!grammar::decodeTerminalSet(payload, set, error)) throw std::runtime_error(error);
    grammar::TerminalSetPayloadInfo info;
    grammar::peekTerminalSet(payload, info, error);
    Json records = Json::array();
    for (const grammar::TerminalRecord& record : set.records) {
        const grammar::Terminal t = grammar::unpackTerminal(record);
        records.push_back({{"position", vec(t.position)},
                           {"building", t.building},
                           {"shape", t.shape},
                           {"size", Json::array({t.size.x, t.size.y})},
                           {"depth_ratio", t.depthRatio},
                           {"axis_x", vec(t.axisX())},
                           {"axis_y", vec(t.axisY())},
                           {"normal", vec(t.normal())}});
    }
    const grammar::TerminalSetHeader& h = set.header;
    return {{"checksum", hex(info.checksum)},
            {"cell", Json::array({h.cell.q, h.cell.r})},
            {"grammar", h.grammar},
            {"grammar_hash", hex(h.grammarHash)},
            {"key", hex(h.key)},
            {"origin", Json::array({h.cellOrigin[0], h.cellOrigin[1], h.cellOrigin[2]})},
            {"count_per_shape", set.countPerShape},
            {"records", records}};
}

Json extrudedExpectation(const std::vector<uint8_t>& payload) {
    grammar::ExtrudedSetHeader h;
    grammar::ExtrudedSet set;
    std::string error;
    if (!grammar::decodeExtrudedSet(payload, h, set, error)) throw std::runtime_error(error);
    Json buildings = Json::array();
    for (const grammar::ExtrudedBuilding& b : set.buildings) {
        Json footprint = Json::array(), parameters = Json::array();
        for (uint32_t v = 0; v < b.vertexCount; ++v)
            footprint.push_back({set.footprints[b.firstVertex + v].x, set.footprints[b.firstVertex + v].y});
        const size_t p = set.buildings.empty() ? 0 : set.parameters.size() / set.buildings.size();
        for (size_t j = 0; j < p; ++j) parameters.push_back(set.parameters[b.firstParameter + j]);
        buildings.push_back({{"id", b.building},
                             {"base_elevation", b.baseElevation},
                             {"height", b.height},
                             {"wall_material", b.wallMaterial},
                             {"footprint", footprint},
                             {"element_count", b.elementCount},
                             {"parameters", parameters}});
    }
    Json elements = Json::array();
    for (const grammar::ExtrudedElement& e : set.elements)
        elements.push_back({{"origin", vec(e.origin)},
                            {"axis_x", vec(e.axisX)},
                            {"axis_y", vec(e.axisY)},
                            {"size", Json::array({e.size.x, e.size.y})},
                            {"rule", e.rule},
                            {"atom", e.atom}});
    return {{"cell", Json::array({h.cell.q, h.cell.r})},
            {"grammar", h.grammar},
            {"key", hex(h.key)},
            {"origin", Json::array({h.cellOrigin[0], h.cellOrigin[1], h.cellOrigin[2]})},
            {"buildings", buildings},
            {"elements", elements}};
}

Json layoutExpectation(uint32_t grid, impostor::ViewSphere sphere) {
    impostor::ViewLayout layout;
    layout.grid = grid;
    layout.sphere = sphere;
    Json views = Json::array();
    for (uint32_t i = 0; i < layout.viewCount(); ++i) {
        const glm::vec3 d = layout.direction(i);
        const impostor::ViewBasis basis = impostor::viewBasis(layout.sphere, d);
        const glm::uvec2 tile = layout.tileOrigin(i);
        views.push_back({{"direction", vec(d)},
                         {"right", vec(basis.right)},
                         {"up", vec(basis.up)},
                         {"tile", Json::array({tile.x, tile.y})}});
    }
    // The GPU's table of views and weights at the renderer's resolution for the sphere.
    const uint32_t resolution = sphere == impostor::ViewSphere::Hemisphere
                                    ? impostor::kFacadeTableResolution
                                    : impostor::kSpeciesTableResolution;
    const impostor::DirectionTable table = impostor::ViewLookup(layout).buildTable(resolution);
    Json tableViews = Json::array(), tableWeights = Json::array();
    for (const impostor::ViewWeights& texel : table.texels) {
        for (int k = 0; k < 4; ++k) {
            tableViews.push_back(texel.views[k]);
            tableWeights.push_back(texel.weights[k]);
        }
    }
    return {
        {"grid", grid},
        {"sphere", sphere == impostor::ViewSphere::Hemisphere ? "hemi-octahedral" : "octahedral"},
        {"view_resolution", layout.viewResolution},
        {"padding", layout.padding},
        {"views", views},
        {"direction_table", {{"resolution", resolution}, {"views", tableViews}, {"weights", tableWeights}}}};
}

} // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::cerr << "usage: web_golden_payloads OUTPUT_FOLDER\n";
        return 2;
    }
    try {
        const std::filesystem::path out = argv[1];
        std::filesystem::create_directories(out);
        for (const auto& [name, buildings] : {std::pair{"residential", 40u}, std::pair{"business", 3u}}) {
            const grammar::BatchResult batch = expand(name, buildings, 42);
            const std::vector<uint8_t> terminals = grammar::encodeTerminalSet(batch.terminals);
            grammar::ExtrudedSetHeader header;
            header.cell = batch.terminals.header.cell;
            header.grammar = batch.terminals.header.grammar;
            header.grammarHash = batch.terminals.header.grammarHash;
            header.key = batch.terminals.header.key;
            std::copy(std::begin(batch.terminals.header.cellOrigin),
                      std::end(batch.terminals.header.cellOrigin), header.cellOrigin);
            const std::vector<uint8_t> extruded = grammar::encodeExtrudedSet(header, batch.extruded);
            write(out / (std::string(name) + ".hxt"), terminals);
            write(out / (std::string(name) + ".hxt.json"), terminalExpectation(terminals));
            write(out / (std::string(name) + ".hxe"), extruded);
            write(out / (std::string(name) + ".hxe.json"), extrudedExpectation(extruded));
        }
        write(out / "view_layout.json",
              Json::array({layoutExpectation(8, impostor::ViewSphere::Hemisphere),
                           layoutExpectation(5, impostor::ViewSphere::Hemisphere),
                           layoutExpectation(8, impostor::ViewSphere::FullSphere),
                           layoutExpectation(5, impostor::ViewSphere::FullSphere)}));
        std::cout << "web_golden_payloads: wrote " << out.string() << "\n";
    } catch (const std::exception& e) {
        std::cerr << "web_golden_payloads: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
