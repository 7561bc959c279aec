#include "bench_impostors_command.h"

#include "render_options.h"
#include "svg_plot.h"
#include "walk_report.h"

#include "hexlod/grammar/rule_reachability.h"
#include "hexlod/impostor/impostor_reconstruction.h"
#include "hexlod/impostor/impostor_store.h"
#include "hexlod/render/image_metrics.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <set>

namespace hexlod::apps {
namespace {

struct Shape {
    std::string name;
    const render::TerminalMesh* mesh;
};

struct Row {
    std::string shape;
    uint32_t grid = 0;
    double bakeSeconds = 0.0;
    uint64_t exrBytes = 0, gpuBytes = 0;
    double meanPsnr = 0.0, worstPsnr = 0.0;
};

// Every distinct mesh of a shape the scene's buildings can emit, as `hexlod bake` chooses them.
std::vector<Shape> emittedShapes(const CitySession& session) {
    std::vector<Shape> out;
    std::set<const render::TerminalMesh*> seen;
    const scene::BuiltScene& scene = session.catalog->scene();
    for (uint32_t g = 0; g < scene.buildingGrammars.size(); ++g) {
        if (scene.buildingGrammars[g].buildings.empty()) continue;
        const std::vector<bool> emitted = grammar::emittedShapes(scene.buildingGrammars[g].grammar);
        for (uint16_t s = 0; s < emitted.size(); ++s) {
            const render::TerminalMesh& mesh = session.meshes->mesh(g, s);
            if (emitted[s] && seen.insert(&mesh).second) out.push_back({mesh.shape, &mesh});
        }
    }
    return out;
}

// Directions within 60 degrees of the facade normal, where LOD3 is drawn; the same for every
// grid, so the sizes are compared on the same views. Exact grid directions are not avoided:
// at random they are rare, and they are part of what a viewer sees.
std::vector<glm::vec3> sampleDirections(uint32_t count) {
    std::mt19937 random(17);
    std::uniform_real_distribution<float> spread(-1.0f, 1.0f);
    std::vector<glm::vec3> out;
    while (out.size() < count) {
        const glm::vec3 d(spread(random), spread(random), 1.0f);
        if (glm::length(glm::vec2(d)) <= std::tan(glm::radians(60.0f))) out.push_back(glm::normalize(d));
    }
    return out;
}

// PSNR is infinite for identical images; the table caps it so means stay finite.
double cappedPsnr(double psnr) {
    return std::min(psnr, 99.0);
}

bool measure(impostor::ImpostorBaker& baker, const Shape& shape, const impostor::ViewLayout& layout,
             const std::vector<glm::vec3>& directions, const std::string& scratch, Row& row,
             std::string& error) {
    const impostor::BakeGeometry geometry = impostor::geometryFromMesh(*shape.mesh);
    impostor::ImpostorAtlas atlas;
    const auto start = std::chrono::steady_clock::now();
    if (!baker.bake(geometry, layout, atlas, error)) return false;
    row.bakeSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    atlas.shape = shape.name;
    atlas.contentKey = impostor::bakeKey(geometry.hash, shape.mesh->nominalSize, layout);
    const std::string file = scratch + "/" + shape.name + ".exr";
    if (!impostor::writeImpostorFile(file, atlas, error)) return false;
    row.exrBytes = std::filesystem::file_size(file);
    std::filesystem::remove(file);
    row.gpuBytes = atlas.byteSize();
    const impostor::ViewLookup lookup(layout);
    std::vector<double> psnr;
    for (const glm::vec3& d : directions) {
        render::Image albedo, normalDepth;
        if (!baker.renderDirection(geometry, layout, d, albedo, normalDepth, error)) return false;
        impostor::Reconstruction rebuilt;
        if (!impostor::reconstructView(atlas, lookup, d, layout.innerResolution(), {}, rebuilt)) {
            error = "no views for a direction";
            return false;
        }
        psnr.push_back(cappedPsnr(render::compareImages(rebuilt.albedo, albedo, true).psnr));
    }
    row.meanPsnr = 0.0;
    for (double p : psnr) row.meanPsnr += p / double(psnr.size());
    row.worstPsnr = *std::min_element(psnr.begin(), psnr.end());
    return true;
}

bool writeReports(const BenchImpostorsOptions& o, const std::vector<Row>& rows, nlohmann::json& perGrid,
                  std::string& error) {
    const std::filesystem::path out(o.outDir);
    std::ofstream csv(out / "impostors.csv");
    csv << "shape,grid,view_resolution,bake_seconds,exr_bytes,gpu_bytes,mean_psnr_db,worst_psnr_db\n";
    for (const Row& r : rows)
        csv << r.shape << ',' << r.grid << ',' << o.resolution << ',' << r.bakeSeconds << ',' << r.exrBytes
            << ',' << r.gpuBytes << ',' << r.meanPsnr << ',' << r.worstPsnr << '\n';
    PlotSeries meanByGrid{"mean over shapes", {}, {}}, worstByGrid{"worst shape", {}, {}, true};
    PlotSeries byBytes{"mean over shapes", {}, {}};
    for (const nlohmann::json& g : perGrid) {
        meanByGrid.x.push_back(g["grid"].get<double>());
        meanByGrid.y.push_back(g["mean_psnr_db"]);
        worstByGrid.x.push_back(g["grid"].get<double>());
        worstByGrid.y.push_back(g["worst_psnr_db"]);
        byBytes.x.push_back(g["exr_bytes"].get<double>() / 1048576.0);
        byBytes.y.push_back(g["mean_psnr_db"]);
    }
    std::ofstream(out / "impostors.json") << nlohmann::json{{"grids", perGrid}}.dump(2) << "\n";
    return writeSvgPlot((out / "error_vs_grid.svg").string(), "4-view blend against a direct render",
                        "views per side N", "PSNR over covered pixels (dB)", {meanByGrid, worstByGrid},
                        error) &&
           writeSvgPlot((out / "error_vs_bytes.svg").string(), "4-view blend against impostor bytes",
                        "EXR bytes of every shape (MiB)", "PSNR over covered pixels (dB)", {byBytes}, error);
}

} // namespace

void registerBenchImpostorsCommand(CLI::App& bench, BenchImpostorsOptions& o, CLI::App*& command) {
    CLI::App* cmd = bench.add_subcommand(
        "impostors", "Impostor bake time, bytes and 4-view blend error against the view grid size");
    cmd->add_option("--scene", o.scenePath, "Scene config (docs/scene.md)")->required();
    cmd->add_option("--out", o.outDir, "Folder for impostors.csv, impostors.json and the SVG plots")
        ->required();
    cmd->add_option("--grids", o.grids, "Views per side of the sweep (2 to 32)")->delimiter(',');
    cmd->add_option("--res", o.resolution, "Texels per view side (16 to 1024)")->capture_default_str();
    cmd->add_option("--directions", o.directions, "Compared directions per shape (1 to 1000)")
        ->capture_default_str();
    cmd->add_option("--gl", o.backend, "GL backend: auto, egl-device, egl-surfaceless, osmesa");
    cmd->add_flag("--json", o.json, "Print the per-grid summary as JSON");
    command = cmd;
}

int runBenchImpostorsCommand(const BenchImpostorsOptions& o) {
    RenderOptions render;
    render.backend = o.backend;
    render.impostorResolution = o.resolution;
    RenderSetup setup;
    std::string error;
    if (!makeRenderSetup(render, setup, error)) {
        std::cerr << "hexlod bench impostors: " << error << "\n";
        return 2;
    }
    for (uint32_t grid : o.grids) {
        if (grid < impostor::kMinGrid || grid > impostor::kMaxGrid ||
            grid * o.resolution > impostor::kMaxAtlasSize) {
            std::cerr << "hexlod bench impostors: --grids: " << grid
                      << " is outside [2, 32] or makes an atlas over " << impostor::kMaxAtlasSize
                      << " texels\n";
            return 2;
        }
    }
    if (o.directions == 0 || o.directions > 1000) {
        std::cerr << "hexlod bench impostors: --directions: " << o.directions << " is outside [1, 1000]\n";
        return 2;
    }
    CitySession session;
    if (int code = openCity("bench impostors", o.scenePath, session)) return code;
    // A context of its own: the sweep bakes for itself, not the scene's impostors.
    render::GlContextResult gl = render::createGlContext({setup.backend, true});
    if (!gl.context) {
        std::cerr << "hexlod bench impostors: " << gl.error() << "\n";
        return 1;
    }
    session.notes.push_back(glContextNote(*gl.context));
    for (const std::string& note : session.notes)
        std::fprintf(stderr, "hexlod bench impostors: %s\n", note.c_str());
    const std::vector<Shape> shapes = emittedShapes(session);
    if (shapes.empty()) {
        std::cerr << "hexlod bench impostors: the scene's buildings emit no shape: nothing to bake\n";
        return 2;
    }
    impostor::ImpostorBaker baker;
    if (!baker.init(error)) {
        std::cerr << "hexlod bench impostors: " << error << "\n";
        return 1;
    }
    const std::filesystem::path scratch = std::filesystem::path(o.outDir) / "scratch";
    std::filesystem::create_directories(scratch);
    const std::vector<glm::vec3> directions = sampleDirections(o.directions);
    std::vector<Row> rows;
    nlohmann::json perGrid = nlohmann::json::array();
    if (!o.json)
        std::printf("grid  bake s  EXR MiB  GPU MiB  mean dB  worst dB   (%zu shapes)\n", shapes.size());
    for (uint32_t grid : o.grids) {
        const impostor::ViewLayout layout{impostor::ViewSphere::Hemisphere, grid, o.resolution, 2};
        if (!layout.validate(error)) {
            std::cerr << "hexlod bench impostors: grid " << grid << ": " << error << "\n";
            return 2;
        }
        Row total;
        std::vector<double> bakeTimes;
        total.worstPsnr = 1e9;
        for (const Shape& shape : shapes) {
            Row row{shape.name, grid};
            if (!measure(baker, shape, layout, directions, scratch.string(), row, error)) {
                std::cerr << "hexlod bench impostors: " << shape.name << ", grid " << grid << ": " << error
                          << "\n";
                return 1;
            }
            total.bakeSeconds += row.bakeSeconds;
            bakeTimes.push_back(row.bakeSeconds);
            total.exrBytes += row.exrBytes;
            total.gpuBytes += row.gpuBytes;
            total.meanPsnr += row.meanPsnr / double(shapes.size());
            total.worstPsnr = std::min(total.worstPsnr, row.worstPsnr);
            rows.push_back(row);
        }
        perGrid.push_back({{"grid", grid},
                           {"view_resolution", o.resolution},
                           {"shapes", shapes.size()},
                           {"bake_seconds", total.bakeSeconds},
                           {"median_bake_seconds_per_shape", median(bakeTimes)},
                           {"exr_bytes", total.exrBytes},
                           {"gpu_bytes", total.gpuBytes},
                           {"mean_psnr_db", total.meanPsnr},
                           {"worst_psnr_db", total.worstPsnr}});
        if (!o.json)
            std::printf("%4u  %6.2f  %7.2f  %7.2f  %7.2f  %8.2f\n", grid, total.bakeSeconds,
                        double(total.exrBytes) / 1048576.0, double(total.gpuBytes) / 1048576.0,
                        total.meanPsnr, total.worstPsnr);
    }
    std::filesystem::remove_all(scratch);
    if (!writeReports(o, rows, perGrid, error)) {
        std::cerr << "hexlod bench impostors: " << error << "\n";
        return 1;
    }
    if (o.json) std::printf("%s\n", perGrid.dump().c_str());
    return 0;
}

} // namespace hexlod::apps
