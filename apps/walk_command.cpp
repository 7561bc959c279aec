#include "walk_command.h"

#include "svg_plot.h"
#include "walk_report.h"

#include "hexlod/render/image_io.h"
#include "hexlod/scene/camera_path.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

namespace hexlod::apps {

CLI::App* registerWalkCommand(CLI::App& app, WalkOptions& o) {
    CLI::App* cmd = app.add_subcommand(
        "walk", "Render a camera path headless through the LOD system and report every frame");
    cmd->add_option("--scene", o.scenePath, "Scene config (docs/scene.md)")->required();
    cmd->add_option("--path", o.pathPath, "Camera path (docs/scene.md, \"Camera paths\")")->required();
    cmd->add_option("--frames", o.frames, "Frames, evenly spread over the path");
    cmd->add_option("--out", o.outDir, "Folder for frames.json, frames.csv, summary.json, frame_ms.svg");
    cmd->add_flag("--png", o.png, "Also write every frame as PNG into --out");
    cmd->add_option("--profile", o.profilePath, "LOD profile overriding the scene's (docs/scene.md)");
    cmd->add_flag("--reference", o.reference, "Draw everything at LOD4 (the error reports' reference)");
    cmd->add_option("--mode", o.mode, "lod, or one LOD forced on everything: lod4, lod3, lod2, lod1, lod0");
    cmd->add_flag("--json", o.json, "Print the summary as one JSON object");
    cmd->add_flag("--time-passes", o.timePasses,
                  "Time every draw pass (pass_ms): GL timestamps on a GPU, else a finish after each pass, "
                  "which slows the frame a little");
    cmd->add_flag("--keep-hidden", o.keepHidden,
                  "Draw what the occluders hide instead of culling it, to measure what culling saves");
    addRenderOptions(*cmd, o.render);
    return cmd;
}

int runWalkCommand(const WalkOptions& o) {
    lod::RenderMode mode = lod::RenderMode::Lod;
    if (!lod::parseRenderMode(o.reference ? "lod4" : o.mode, mode)) {
        std::cerr << "hexlod walk: --mode: unknown mode '" << o.mode
                  << "' (lod, lod4, lod3, lod2, lod1, lod0)\n";
        return 2;
    }
    if (o.frames == 0 || o.frames > 100000) {
        std::cerr << "hexlod walk: --frames: " << o.frames << " is outside [1, 100000]\n";
        return 2;
    }
    if (o.png && o.outDir.empty()) {
        std::cerr << "hexlod walk: --png needs --out\n";
        return 2;
    }
    RenderSetup setup;
    std::string error;
    if (!makeRenderSetup(o.render, setup, error)) {
        std::cerr << "hexlod walk: " << error << "\n";
        return 2;
    }
    scene::CameraPath path;
    if (!scene::loadCameraPath(o.pathPath, path, error)) {
        std::cerr << "hexlod walk: " << error << "\n";
        return 2;
    }
    CitySession session;
    if (int code = openCity("walk", o.scenePath, session)) return code;
    scene::LodProfile profile = session.config.lod;
    if (!o.profilePath.empty() && !scene::loadLodProfile(o.profilePath, profile, error)) {
        std::cerr << "hexlod walk: " << error << "\n";
        return 2;
    }
    setup.impostors = mode != lod::RenderMode::AllLod4;
    setup.progress = !o.json;
    if (int code = openRenderer("walk", setup, session)) return code;

    lod::CityRendererOptions options;
    options.width = o.render.width ? o.render.width : path.viewportWidth;
    options.height = o.render.height ? o.render.height : path.viewportHeight;
    options.mode = mode;
    options.lod = profile;
    options.schedulerWorkers = o.render.workers;
    options.samples = o.render.samples;
    if (o.timePasses)
        options.passClock = session.gl->info().gpuTimestamps() ? lod::PassClock::GpuTimestamps
                                                               : lod::PassClock::FinishAndWall;
    options.dropHidden = !o.keepHidden;
    lod::CityRenderer renderer(*session.catalog, *session.cache, *session.meshes, &session.impostors,
                               options);
    if (!renderer.init(error)) {
        std::cerr << "hexlod walk: " << error << "\n";
        return 1;
    }
    session.notes.push_back(renderer.summary());
    if (!renderer.coarseNote().empty()) session.notes.push_back(renderer.coarseNote());
    if (std::string note = renderer.arenaNote(); !note.empty()) session.notes.push_back(note);
    for (const std::string& note : session.notes) std::fprintf(stderr, "hexlod walk: %s\n", note.c_str());
    if (!o.outDir.empty()) std::filesystem::create_directories(o.outDir);
    const glm::dvec3 origin = path.relativeToSceneCentre ? sceneCentre(*session.catalog) : glm::dvec3(0.0);
    const std::vector<scene::CameraPose> poses = path.sample(o.frames, origin);
    std::vector<lod::FrameStats> frames;
    nlohmann::json perFrame = nlohmann::json::array();
    for (size_t f = 0; f < poses.size(); ++f) {
        const double time = path.keyframes.front().time +
                            (poses.size() > 1 ? path.duration() * double(f) / double(poses.size() - 1) : 0.0);
        frames.push_back(renderer.render(poses[f], time, path.nearPlane, path.farPlane));
        perFrame.push_back(frameJson(frames.back()));
        if (o.png) {
            char name[32];
            std::snprintf(name, sizeof name, "frame_%05zu.png", f);
            if (!render::writePng((std::filesystem::path(o.outDir) / name).string(), renderer.readColor(),
                                  error)) {
                std::cerr << "hexlod walk: " << error << "\n";
                return 1;
            }
        }
    }
    nlohmann::json summary = summarizeFrames(frames);
    summary["scene"] = session.config.name;
    summary["path"] = path.name;
    summary["mode"] = lod::renderModeName(mode);
    summary["viewport"] = {options.width, options.height};
    summary["gl_renderer"] = session.gl->info().renderer;
    summary["pass_clock"] = lod::passClockName(options.passClock);
    summary["notes"] = session.notes;
    summary["peak_rss_bytes"] = peakRssBytes();
    summary["cache_budget_bytes"] = session.config.cache.memoryBytes;
    // What the memory tier cost over the walk: sets read back from the disk tier (each one
    // decoded and uploaded again) and sets dropped for the budget.
    const cache::CacheStats cacheStats = session.cache->stats();
    summary["cache_disk_loads"] = cacheStats.diskHits;
    summary["cache_evictions"] = cacheStats.evictions;
    if (!o.outDir.empty()) {
        std::ofstream(std::filesystem::path(o.outDir) / "frames.json") << perFrame.dump(1) << "\n";
        std::ofstream(std::filesystem::path(o.outDir) / "summary.json") << summary.dump(2) << "\n";
        if (!writeFramesCsv((std::filesystem::path(o.outDir) / "frames.csv").string(), frames, error)) {
            std::cerr << "hexlod walk: " << error << "\n";
            return 1;
        }
        PlotSeries frameMs{"frame ms", {}, {}}, triangles{"M triangles", {}, {}};
        for (const lod::FrameStats& f : frames) {
            frameMs.x.push_back(double(f.frame));
            frameMs.y.push_back(f.frameMs);
            triangles.x.push_back(double(f.frame));
            triangles.y.push_back(double(f.triangles) / 1e6);
        }
        if (!writeSvgPlot((std::filesystem::path(o.outDir) / "frame_ms.svg").string(),
                          "hexlod walk: " + path.name + " (" + lod::renderModeName(mode) + ")", "frame", "ms",
                          {frameMs}, error) ||
            !writeSvgPlot((std::filesystem::path(o.outDir) / "triangles.svg").string(), "triangles per frame",
                          "frame", "million triangles", {triangles}, error)) {
            std::cerr << "hexlod walk: " << error << "\n";
            return 1;
        }
    }
    if (o.json) {
        std::printf("%s\n", summary.dump().c_str());
    } else {
        std::printf("frames       %zu (%s, %ux%u)\n", frames.size(), lod::renderModeName(mode), options.width,
                    options.height);
        std::printf("frame ms     median %.1f, p95 %.1f\n", summary["median_frame_ms"].get<double>(),
                    summary["p95_frame_ms"].get<double>());
        std::printf("triangles    median %.0f\n", summary["median_triangles"].get<double>());
        std::printf("terminals    LOD4 %.0f, LOD3 %.0f, LOD2 %.0f (medians)\n",
                    summary["terminals_per_lod"]["lod4"].get<double>(),
                    summary["terminals_per_lod"]["lod3"].get<double>(),
                    summary["terminals_per_lod"]["lod2"].get<double>());
        std::printf("resident     peak %.1f MB\n",
                    double(summary["peak_resident_bytes"].get<uint64_t>()) / 1e6);
    }
    return 0;
}

} // namespace hexlod::apps
