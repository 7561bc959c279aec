// The rendering commands end to end on llvmpipe (`hexlod walk`, `bake`, `bench error`, `bench
// impostors`): their JSON contracts, the files they write, a zero-length path, and bad options
// refused by name with exit code 2. Scenes and frames are tiny, so the whole file runs in seconds.
#include "command_runner.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace hexlod::test {
namespace {

using Json = nlohmann::json;

const std::string kScene = std::string(HEXLOD_TESTS_DIR) + "/lod/scenes/three_shapes.json";

// A fresh folder for one test's outputs.
std::string folder(const std::string& name) {
    const std::string dir = ::testing::TempDir() + "hexlod-render-cli-" + name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

// A short path around the three-shapes scene's centre; one keyframe makes a zero-length path.
std::string writePath(const std::string& dir, bool zeroLength = false) {
    Json keyframes = Json::array();
    keyframes.push_back({{"time", 0}, {"position", {-60, -60, 30}}, {"target", {0, 0, 5}}});
    if (!zeroLength) keyframes.push_back({{"time", 4}, {"position", {60, -60, 20}}, {"target", {0, 0, 5}}});
    const Json path = {{"name", "test orbit"},  {"relative_to", "scene_centre"},
                       {"viewport", {96, 64}},  {"fov_y_degrees", 60},
                       {"near", 0.3},           {"far", 5000},
                       {"keyframes", keyframes}};
    const std::string file = dir + (zeroLength ? "/still.json" : "/orbit.json");
    std::ofstream(file) << path.dump();
    return file;
}

TEST(RenderCli, WalkJsonAndItsFiles) {
    const std::string dir = folder("walk");
    const CommandResult r = runHexlod("walk --scene " + kScene + " --path " + writePath(dir) +
                                      " --frames 3 --out " + dir + "/out --png --impostor-grid 2 --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Json j = Json::parse(r.out);
    for (const char* key :
         {"frames", "median_frame_ms", "p95_frame_ms", "median_triangles", "terminals_per_lod",
          "peak_resident_bytes", "notes", "cache_hit_rate", "cache_disk_loads", "cache_evictions"})
        EXPECT_TRUE(j.contains(key)) << key;
    // A fresh cache of the default budget holds this scene: nothing read back, nothing dropped.
    EXPECT_EQ(j["cache_disk_loads"], 0);
    EXPECT_EQ(j["cache_evictions"], 0);
    EXPECT_EQ(j["frames"], 3);
    EXPECT_GT(j["median_triangles"].get<double>(), 0.0);
    EXPECT_TRUE(j["terminals_per_lod"].is_object());
    bool lod1 = false;
    for (const Json& note : j["notes"]) lod1 |= note == "LOD1 shaders: 1 grammar";
    EXPECT_TRUE(lod1) << j["notes"];
    for (const char* file : {"frames.json", "frames.csv", "summary.json", "frame_ms.svg", "frame_00000.png"})
        EXPECT_TRUE(std::filesystem::exists(dir + "/out/" + file)) << file;

    // frames.csv says what frames.json says, column by column, one row per frame.
    const Json frames = Json::parse(std::ifstream(dir + "/out/frames.json"));
    std::ifstream csv(dir + "/out/frames.csv");
    std::string line;
    ASSERT_TRUE(std::getline(csv, line));
    std::vector<std::string> header;
    for (std::stringstream columns(line); std::getline(columns, line, ',');) header.push_back(line);
    const std::map<std::string, Json::json_pointer> sources = {
        {"frame", Json::json_pointer("/frame")},
        {"triangles", Json::json_pointer("/triangles")},
        {"lod4_terminals", Json::json_pointer("/terminals_per_lod/lod4")},
        {"lod4_coarse_terminals", Json::json_pointer("/lod4_coarse_terminals")},
        {"resident_bytes", Json::json_pointer("/resident_bytes")}};
    for (const auto& [name, pointer] : sources)
        EXPECT_NE(std::find(header.begin(), header.end(), name), header.end()) << name;
    size_t rows = 0;
    for (; std::getline(csv, line); ++rows) {
        ASSERT_LT(rows, frames.size());
        std::vector<std::string> cells;
        for (std::stringstream columns(line); std::getline(columns, line, ',');) cells.push_back(line);
        ASSERT_EQ(cells.size(), header.size());
        for (size_t c = 0; c < header.size(); ++c) {
            if (auto source = sources.find(header[c]); source != sources.end()) {
                EXPECT_EQ(cells[c], frames[rows][source->second].dump()) << header[c] << " in row " << rows;
            }
        }
    }
    EXPECT_EQ(rows, frames.size());
    // The base volumes resident are a part of the GPU's bytes.
    for (const Json& frame : frames) {
        EXPECT_TRUE(frame["volumes_shaded_at_mean"].is_number_unsigned());
        // Of the batches uploaded, those whose page bounds a background thread prepared.
        EXPECT_LE(frame["uploads_prepared"].get<uint32_t>(), frame["batches_uploaded"].get<uint32_t>());
        EXPECT_GT(frame["volume_bytes"].get<uint64_t>(), 0u);
        EXPECT_LT(frame["volume_bytes"].get<uint64_t>(), frame["gpu_bytes"].get<uint64_t>());
    }
}

TEST(RenderCli, WalkTimesEveryDrawPassWhenAsked) {
    const std::string dir = folder("passes");
    const std::string walk =
        "walk --scene " + kScene + " --path " + writePath(dir) + " --frames 2 --impostor-grid 2 --json";
    const CommandResult timed = runHexlod(walk + " --time-passes");
    ASSERT_EQ(timed.exitCode, 0) << timed.err;
    const Json passes = Json::parse(timed.out)["median_pass_ms"];
    double sum = 0.0;
    for (const char* pass : {"terminal_meshes", "lod0", "lod1", "ground", "impostors", "trees"}) {
        ASSERT_TRUE(passes.contains(pass)) << pass;
        EXPECT_GE(passes[pass].get<double>(), 0.0) << pass;
        sum += passes[pass].get<double>();
    }
    EXPECT_GT(sum, 0.0);
    EXPECT_LE(sum, Json::parse(timed.out)["median_frame_ms"].get<double>());
    // llvmpipe's timestamps are taken before it rasterises: its passes are timed by a finish
    // and the wall clock.
    const std::string clock = Json::parse(timed.out)["pass_clock"];
    const bool software =
        Json::parse(timed.out)["gl_renderer"].get<std::string>().find("llvmpipe") != std::string::npos;
    EXPECT_EQ(clock, software ? "finish-and-wall" : "gpu-timestamps");
    // Untimed, no pass waits for the GL, and none is reported.
    const CommandResult untimed = runHexlod(walk);
    ASSERT_EQ(untimed.exitCode, 0) << untimed.err;
    EXPECT_EQ(Json::parse(untimed.out)["pass_clock"], "off");
    for (const auto& [pass, ms] : Json::parse(untimed.out)["median_pass_ms"].items())
        EXPECT_EQ(ms, 0.0) << pass;
}

// Culling what the occluders hide changes no pixel: --keep-hidden draws it all, and reports
// nothing dropped.
TEST(RenderCli, WalkKeepsHiddenWorkWhenAskedAndDrawsTheSameFrames) {
    const std::string dir = folder("hidden");
    // At street level, across the blocks: the nearest buildings hide the others' facades.
    const Json keyframes = {{{"time", 0}, {"position", {-70, -3, 2}}, {"target", {0, 0, 3}}},
                            {{"time", 2}, {"position", {-70, 8, 2}}, {"target", {0, 0, 3}}}};
    std::ofstream(dir + "/street.json") << Json{
        {"name", "street"},      {"relative_to", "scene_centre"},
        {"viewport", {96, 64}},  {"fov_y_degrees", 60},
        {"near", 0.3},           {"far", 5000},
        {"keyframes", keyframes}}.dump();
    const std::string walk = "walk --scene " + kScene + " --path " + dir +
                             "/street.json --frames 2 --impostor-grid 2 --png --json --out " + dir;
    const CommandResult culled = runHexlod(walk + "/culled");
    ASSERT_EQ(culled.exitCode, 0) << culled.err;
    const CommandResult kept = runHexlod(walk + "/kept --keep-hidden");
    ASSERT_EQ(kept.exitCode, 0) << kept.err;
    uint64_t hidden = 0;
    for (const Json& frame : Json::parse(std::ifstream(dir + "/culled/frames.json")))
        hidden += frame["cull_occluded_terminals"].get<uint64_t>();
    EXPECT_GT(hidden, 0u); // else the comparison below would prove nothing
    const Json frames = Json::parse(std::ifstream(dir + "/kept/frames.json"));
    ASSERT_EQ(frames.size(), 2u);
    for (const Json& frame : frames)
        for (const char* key : {"cull_occluded_terminals", "tree_billboards_occluded", "lod3_occluded",
                                "volumes_occluded", "volume_buildings_occluded"})
            EXPECT_EQ(frame[key], 0) << key;
    const auto bytes = [](const std::string& file) {
        std::ifstream in(file, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(in), {});
    };
    for (const char* frame : {"frame_00000.png", "frame_00001.png"})
        EXPECT_EQ(bytes(dir + "/kept/" + frame), bytes(dir + "/culled/" + frame)) << frame;
}

TEST(RenderCli, AZeroLengthPathRendersItsFrames) {
    const std::string dir = folder("still");
    const CommandResult r = runHexlod("walk --scene " + kScene + " --path " + writePath(dir, true) +
                                      " --frames 2 --mode lod4 --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(Json::parse(r.out)["frames"], 2);
}

TEST(RenderCli, BakeJsonCountsWhatWasBakedAndLeftOut) {
    const std::string dir = folder("bake");
    const std::string bake = "bake --scene " + kScene + " --grid 2 --res 16 --store " + dir + "/store";
    const CommandResult r = runHexlod(bake + " --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Json j = Json::parse(r.out);
    for (const char* key : {"shapes_baked", "shapes_skipped_unused", "bytes", "seconds"})
        EXPECT_TRUE(j.contains(key)) << key;
    EXPECT_EQ(j["shapes_baked"], 3);
    EXPECT_EQ(j["shapes_skipped_unused"], 3);
    EXPECT_GT(j["bytes"].get<uint64_t>(), 0u);
    const CommandResult sheet = runHexlod(bake + " --show window -o " + dir + "/window.png");
    ASSERT_EQ(sheet.exitCode, 0) << sheet.err;
    EXPECT_TRUE(std::filesystem::exists(dir + "/window.png"));
    const CommandResult unknown = runHexlod(bake + " --show castle -o " + dir + "/castle.png");
    EXPECT_EQ(unknown.exitCode, 2);
    EXPECT_NE(unknown.err.find("no impostor named 'castle'"), std::string::npos) << unknown.err;
}

TEST(RenderCli, BenchErrorJsonHasOneEntryPerSetting) {
    const std::string dir = folder("error");
    const CommandResult r = runHexlod("bench error --scene " + kScene + " --path " + writePath(dir) +
                                      " --frames 2 --sse 2,8 --impostor-grid 2 --out " + dir + "/out --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Json entries = Json::parse(r.out);
    ASSERT_EQ(entries.size(), 7u); // the reference, two sweep values, four forced LODs
    for (const Json& e : entries)
        for (const char* key :
             {"setting", "median_frame_ms", "frame_time_ratio_to_reference", "mean_psnr_db", "mean_ssim"})
            EXPECT_TRUE(e.contains(key)) << key;
    EXPECT_EQ(entries[0]["frame_time_ratio_to_reference"], 1.0);
    EXPECT_GT(entries[1]["mean_psnr_db"].get<double>(), 10.0);
    for (const char* file : {"error.csv", "error.json", "error_vs_time.svg", "contact_sheet.png"})
        EXPECT_TRUE(std::filesystem::exists(dir + "/out/" + file)) << file;
}

TEST(RenderCli, BenchErrorAgainstASupersampledReferenceMeasuresTheReferenceToo) {
    const std::string dir = folder("error-supersampled");
    const CommandResult r =
        runHexlod("bench error --scene " + kScene + " --path " + writePath(dir) +
                  " --frames 2 --sse 2 --no-forced --impostor-grid 2 --reference-supersample 2 "
                  "--out " +
                  dir + " --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Json entries = Json::parse(r.out);
    ASSERT_EQ(entries.size(), 2u);
    // The timed reference is still the ratios' denominator, and now has an error of its own:
    // its aliasing against the filtered ground truth.
    EXPECT_EQ(entries[0]["frame_time_ratio_to_reference"], 1.0);
    ASSERT_TRUE(entries[0]["mean_psnr_db"].is_number());
    EXPECT_GT(entries[0]["mean_psnr_db"].get<double>(), 20.0);
    EXPECT_LT(entries[0]["mean_psnr_db"].get<double>(), 99.0)
        << "a one-sample render is not its supersampled self";
    EXPECT_GT(entries[1]["mean_psnr_db"].get<double>(), 10.0);
}

TEST(RenderCli, BenchImpostorsSweepsTheGrid) {
    const std::string dir = folder("impostors");
    const CommandResult r = runHexlod("bench impostors --scene " + kScene +
                                      " --grids 2,4 --res 16 --directions 3 "
                                      "--out " +
                                      dir + " --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const Json grids = Json::parse(r.out);
    ASSERT_EQ(grids.size(), 2u);
    EXPECT_EQ(grids[0]["shapes"], 3);
    EXPECT_LT(grids[0]["exr_bytes"].get<uint64_t>(), grids[1]["exr_bytes"].get<uint64_t>());
    EXPECT_LT(grids[0]["mean_psnr_db"].get<double>(), grids[1]["mean_psnr_db"].get<double>())
        << "more views, less error";
    for (const char* file : {"impostors.csv", "impostors.json", "error_vs_grid.svg", "error_vs_bytes.svg"})
        EXPECT_TRUE(std::filesystem::exists(dir + "/" + file)) << file;
    EXPECT_FALSE(std::filesystem::exists(dir + "/scratch"));
}

TEST(RenderCli, WalkRefusesMoreSamplesThanTheGlAllows) {
    // 64 passes the option's own bounds; no GL multisamples a colour target 64 times.
    const std::string dir = folder("samples");
    const CommandResult r = runHexlod("walk --scene " + kScene + " --path " + writePath(dir) +
                                      " --frames 1 --impostor-grid 2 --samples 64 --out " + dir);
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.err.find("64 samples per pixel, this GL allows 1 to"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("baking"), std::string::npos) << "refused only after baking the impostors";
}

TEST(RenderCli, BadOptionsAreRefusedByName) {
    const std::string dir = folder("bad");
    const std::string path = writePath(dir);
    const struct {
        std::string arguments, message;
    } cases[] = {
        {"walk --scene " + kScene + " --path " + path + " --gl vulkan", "--gl: unknown backend 'vulkan'"},
        {"walk --scene " + kScene + " --path " + path + " --impostor-grid 40", "--impostor-grid: 40"},
        {"walk --scene " + kScene + " --path " + dir + "/missing.json", "missing.json"},
        {"bake --scene " + kScene + " --show window", "--show needs -o"},
        {"bench error --scene " + kScene + " --path " + path + " --out " + dir + " --sse 0", "--sse: 0"},
        {"bench error --scene " + kScene + " --path " + path + " --out " + dir + " --reference-supersample 0",
         "--reference-supersample: 0"},
        {"bench error --scene " + kScene + " --path " + path + " --out " + dir + " --reference-supersample 5",
         "--reference-supersample: 5"},
        {"bench error --scene " + kScene + " --path " + path + " --out " + dir + " --repeats 0",
         "--repeats: 0"},
        {"bench error --scene " + kScene + " --path " + path + " --out " + dir + " --repeats 101",
         "--repeats: 101"},
        {"walk --scene " + kScene + " --path " + path + " --samples 0", "--samples: 0"},
        {"bench error --scene " + kScene + " --path " + path + " --out " + dir + " --samples 65",
         "--samples: 65"},
        {"bench impostors --scene " + kScene + " --out " + dir + " --grids 1", "--grids: 1"},
        {"bench impostors --scene " + kScene + " --out " + dir + " --directions 0", "--directions: 0"},
    };
    for (const auto& c : cases) {
        const CommandResult r = runHexlod(c.arguments);
        EXPECT_EQ(r.exitCode, 2) << c.arguments << "\n" << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.arguments << "\n" << r.err;
    }
}

} // namespace
} // namespace hexlod::test
