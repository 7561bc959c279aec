#include "bench_error_command.h"

#include "svg_plot.h"
#include "walk_report.h"

#include "hexlod/render/image_io.h"
#include "hexlod/render/image_metrics.h"
#include "hexlod/scene/camera_path.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

namespace hexlod::apps {
namespace {

struct Setting {
    std::string name;
    lod::RenderMode mode;
    double sse; // the profile's maxScreenSpaceError
};

struct SettingResult {
    Setting setting;
    std::vector<lod::FrameStats> frames;
    std::vector<double> psnr, ssim;
    render::Image sample; // the path's middle frame, for the contact sheet
    render::Image error;  // its difference to the reference's, magnified, for the heat-map sheet
};

// |a - b| per channel, times 4 so a 1/4 error saturates: where a setting's error sits.
render::Image difference(const render::Image& a, const render::Image& b) {
    render::Image d(a.width, a.height, 4, 1.0f);
    for (size_t i = 0; i < a.pixels.size(); ++i)
        if (i % 4 != 3) d.pixels[i] = std::min(1.0f, 4.0f * std::abs(a.pixels[i] - b.pixels[i]));
    return d;
}

// Pixels of `images` side by side, each labelled by nothing but its place (the table says which).
render::Image sideBySide(const std::vector<const render::Image*>& images, uint32_t columns) {
    const uint32_t w = images.front()->width, h = images.front()->height, gap = 4;
    const uint32_t rows = uint32_t((images.size() + columns - 1) / columns);
    render::Image sheet(columns * (w + gap) - gap, rows * (h + gap) - gap, 4, 1.0f);
    for (size_t i = 0; i < images.size(); ++i) {
        const uint32_t ox = uint32_t(i % columns) * (w + gap), oy = uint32_t(i / columns) * (h + gap);
        for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x) std::copy_n(images[i]->at(x, y), 4, sheet.at(ox + x, oy + y));
    }
    return sheet;
}

std::vector<double> frameMs(const std::vector<lod::FrameStats>& frames) {
    std::vector<double> ms;
    for (const lod::FrameStats& f : frames) ms.push_back(f.frameMs);
    return ms;
}

} // namespace

void registerBenchErrorCommand(CLI::App& bench, BenchErrorOptions& o, CLI::App*& command) {
    CLI::App* cmd = bench.add_subcommand(
        "error", "Image error against frame time: the LOD system and forced LODs against all-LOD4");
    cmd->add_option("--scene", o.scenePath, "Scene config (docs/scene.md)")->required();
    cmd->add_option("--path", o.pathPath, "Camera path (docs/scene.md, \"Camera paths\")")->required();
    cmd->add_option("--frames", o.frames, "Frames per setting, evenly spread over the path");
    cmd->add_option("--out", o.outDir,
                    "Folder for error.csv, error.json, error_vs_time.svg, contact_sheet.png")
        ->required();
    cmd->add_option("--sse", o.sse, "maxScreenSpaceError values of the sweep, in pixels")->delimiter(',');
    cmd->add_flag("!--no-forced", o.forced, "Leave out the forced LOD3, LOD2, LOD1 and LOD0 renders");
    cmd->add_flag("--json", o.json, "Print one JSON entry per setting");
    cmd->add_flag("--keep-hidden", o.keepHidden,
                  "Every setting, the reference too, draws what the occluders hide instead of culling it");
    cmd->add_option("--repeats", o.repeats,
                    "Timed passes over the path per setting; each frame's time is the median of its passes "
                    "(1 to 100; the images and counts are the first pass's)");
    cmd->add_option(
        "--reference-supersample", o.referenceSupersample,
        "Measure errors against all-LOD4 rendered at N times the size and filtered down (1 to 4)");
    addRenderOptions(*cmd, o.render);
    command = cmd;
}

int runBenchErrorCommand(const BenchErrorOptions& o) {
    RenderSetup setup;
    std::string error;
    if (!makeRenderSetup(o.render, setup, error)) {
        std::cerr << "hexlod bench error: " << error << "\n";
        return 2;
    }
    if (o.frames == 0 || o.frames > 10000) {
        std::cerr << "hexlod bench error: --frames: " << o.frames << " is outside [1, 10000]\n";
        return 2;
    }
    if (o.repeats == 0 || o.repeats > 100) {
        std::cerr << "hexlod bench error: --repeats: " << o.repeats << " is outside [1, 100]\n";
        return 2;
    }
    for (double sse : o.sse) {
        if (!(sse >= 0.01 && sse <= 1000.0)) {
            std::cerr << "hexlod bench error: --sse: " << sse << " is outside [0.01, 1000]\n";
            return 2;
        }
    }
    if (o.referenceSupersample == 0 || o.referenceSupersample > 4) {
        std::cerr << "hexlod bench error: --reference-supersample: " << o.referenceSupersample
                  << " is outside [1, 4]\n";
        return 2;
    }
    scene::CameraPath path;
    if (!scene::loadCameraPath(o.pathPath, path, error)) {
        std::cerr << "hexlod bench error: " << error << "\n";
        return 2;
    }
    CitySession session;
    if (int code = openCity("bench error", o.scenePath, session)) return code;
    setup.progress = !o.json;
    if (int code = openRenderer("bench error", setup, session)) return code;
    // What was started and left out goes to stderr, so that --json keeps stdout to the entries.
    for (const std::string& note : session.notes)
        std::fprintf(stderr, "hexlod bench error: %s\n", note.c_str());
    std::filesystem::create_directories(o.outDir);

    std::vector<Setting> settings{
        {"lod4 (reference)", lod::RenderMode::AllLod4, session.config.lod.maxScreenSpaceError}};
    for (double sse : o.sse)
        settings.push_back({"lod sse " + std::to_string(sse).substr(0, 4), lod::RenderMode::Lod, sse});
    if (o.forced) {
        for (lod::RenderMode mode : {lod::RenderMode::AllLod3, lod::RenderMode::AllLod2,
                                     lod::RenderMode::AllLod1, lod::RenderMode::AllLod0})
            settings.push_back({std::string("forced ") + lod::renderModeName(mode), mode,
                                session.config.lod.maxScreenSpaceError});
    }
    const glm::dvec3 origin = path.relativeToSceneCentre ? sceneCentre(*session.catalog) : glm::dvec3(0.0);
    const std::vector<scene::CameraPose> poses = path.sample(o.frames, origin);
    const uint32_t width = o.render.width ? o.render.width : path.viewportWidth;
    const uint32_t height = o.render.height ? o.render.height : path.viewportHeight;

    auto rendererOptions = [&](lod::RenderMode mode, double sse, uint32_t scale) {
        lod::CityRendererOptions options;
        options.width = width * scale;
        options.height = height * scale;
        options.mode = mode;
        options.lod = session.config.lod;
        options.lod.maxScreenSpaceError = sse;
        options.schedulerWorkers = 0;
        options.samples = o.render.samples;
        options.dropHidden = !o.keepHidden;
        return options;
    };
    // What errors are measured against: the reference's own frames, or with
    // --reference-supersample the same all-LOD4 frames at N times the size, filtered down, so
    // that detail finer than a pixel counts as its average colour, not as the reference's
    // aliasing of it.
    std::vector<render::Image> truth;
    if (o.referenceSupersample > 1) {
        lod::CityRenderer renderer(
            *session.catalog, *session.cache, *session.meshes, &session.impostors,
            rendererOptions(lod::RenderMode::AllLod4, settings.front().sse, o.referenceSupersample));
        if (!renderer.init(error)) {
            std::cerr << "hexlod bench error: supersampled reference: " << error << "\n";
            return 1;
        }
        if (!o.json)
            std::fprintf(stderr, "hexlod bench error: lod4 at %ux (ground truth)\n", o.referenceSupersample);
        for (size_t f = 0; f < poses.size(); ++f) {
            renderer.render(poses[f], double(f), path.nearPlane, path.farPlane);
            truth.push_back(render::boxDownsample(renderer.readColor(), o.referenceSupersample));
        }
    }

    std::vector<render::Image> reference;
    std::vector<SettingResult> results;
    bool coarseReported = false;
    for (const Setting& setting : settings) {
        lod::CityRenderer renderer(*session.catalog, *session.cache, *session.meshes, &session.impostors,
                                   rendererOptions(setting.mode, setting.sse, 1));
        if (!renderer.init(error)) {
            std::cerr << "hexlod bench error: " << setting.name << ": " << error << "\n";
            return 1;
        }
        if (&setting == &settings.front()) {
            std::fprintf(stderr, "hexlod bench error: %s\n", renderer.summary().c_str());
            if (std::string note = renderer.arenaNote(); !note.empty())
                std::fprintf(stderr, "hexlod bench error: %s\n", note.c_str());
        }
        // The reference draws full meshes: the first LOD system setting reports the coarse ones.
        if (!renderer.coarseNote().empty() && !coarseReported) {
            std::fprintf(stderr, "hexlod bench error: %s\n", renderer.coarseNote().c_str());
            coarseReported = true;
        }
        if (!o.json) std::fprintf(stderr, "hexlod bench error: %s\n", setting.name.c_str());
        SettingResult result;
        result.setting = setting;
        // A first pass generates what the path needs, so the timed pass measures drawing alone.
        for (size_t f = 0; f < poses.size(); ++f)
            renderer.render(poses[f], double(f), path.nearPlane, path.farPlane);
        for (size_t f = 0; f < poses.size(); ++f) {
            result.frames.push_back(
                renderer.render(poses[f], double(poses.size() + f), path.nearPlane, path.farPlane));
            render::Image image = renderer.readColor();
            if (results.empty()) reference.push_back(image);
            const render::Image& against = truth.empty() ? reference[f] : truth[f];
            const bool measured = !results.empty() || !truth.empty();
            if (measured) {
                result.psnr.push_back(render::compareImages(image, against).psnr);
                result.ssim.push_back(render::ssim(image, against));
            }
            if (f == poses.size() / 2) {
                if (measured) result.error = difference(image, against);
                result.sample = std::move(image);
            }
        }
        // The passes after the first only time the frames again.
        std::vector<std::vector<double>> timings(poses.size());
        for (size_t f = 0; f < poses.size(); ++f) timings[f].push_back(result.frames[f].frameMs);
        for (uint32_t pass = 1; pass < o.repeats; ++pass)
            for (size_t f = 0; f < poses.size(); ++f)
                timings[f].push_back(renderer
                                         .render(poses[f], double((pass + 1) * poses.size() + f),
                                                 path.nearPlane, path.farPlane)
                                         .frameMs);
        for (size_t f = 0; f < poses.size(); ++f) result.frames[f].frameMs = median(timings[f]);
        results.push_back(std::move(result));
    }

    const double referenceMs = median(frameMs(results.front().frames));
    nlohmann::json entries = nlohmann::json::array();
    std::ostringstream csv;
    csv << "setting,mode,max_sse,median_frame_ms,frame_time_ratio_to_reference,mean_psnr_db,min_psnr_db,mean_"
           "ssim,"
           "median_triangles,peak_resident_bytes\n";
    PlotSeries lodCurve{"LOD system (sse sweep)", {}, {}, false}, forcedPoints{"forced LOD", {}, {}, true};
    for (const SettingResult& r : results) {
        nlohmann::json summary = summarizeFrames(r.frames);
        const double ms = summary["median_frame_ms"].get<double>();
        double meanPsnr = 0.0, minPsnr = 1e9, meanSsim = 0.0;
        for (double p : r.psnr) meanPsnr += std::min(p, 99.0), minPsnr = std::min(minPsnr, p);
        for (double s : r.ssim) meanSsim += s;
        // The reference has an error only against a supersampled ground truth.
        const bool isReference = r.psnr.empty();
        if (!isReference) meanPsnr /= double(r.psnr.size()), meanSsim /= double(r.ssim.size());
        nlohmann::json entry = {
            {"setting", r.setting.name},
            {"mode", lod::renderModeName(r.setting.mode)},
            {"max_screen_space_error", r.setting.sse},
            {"median_frame_ms", ms},
            {"frame_time_ratio_to_reference", ms / referenceMs},
            {"mean_psnr_db", isReference ? nlohmann::json(nullptr) : nlohmann::json(meanPsnr)},
            {"min_psnr_db", isReference ? nlohmann::json(nullptr) : nlohmann::json(minPsnr)},
            {"mean_ssim", isReference ? nlohmann::json(1.0) : nlohmann::json(meanSsim)},
            {"median_triangles", summary["median_triangles"]},
            {"terminals_per_lod", summary["terminals_per_lod"]},
            {"peak_resident_bytes", summary["peak_resident_bytes"]},
            {"median_stage_ms", summary["median_stage_ms"]},
            {"total_generation_ms", summary["total_generation_ms"]},
            {"frame_ms_per_frame", frameMs(r.frames)},
            {"psnr_db_per_frame", r.psnr},
            {"ssim_per_frame", r.ssim}};
        entries.push_back(entry);
        csv << '"' << r.setting.name << "\"," << lod::renderModeName(r.setting.mode) << ',' << r.setting.sse
            << ',' << ms << ',' << ms / referenceMs << ',' << (isReference ? 0.0 : meanPsnr) << ','
            << (isReference ? 0.0 : minPsnr) << ',' << (isReference ? 1.0 : meanSsim) << ','
            << summary["median_triangles"].get<double>() << ','
            << summary["peak_resident_bytes"].get<uint64_t>() << '\n';
        if (isReference) continue;
        PlotSeries& series = r.setting.mode == lod::RenderMode::Lod ? lodCurve : forcedPoints;
        series.x.push_back(ms / referenceMs);
        series.y.push_back(meanPsnr);
    }
    const std::filesystem::path out(o.outDir);
    std::ofstream(out / "error.csv") << csv.str();
    std::ofstream(out / "error.json") << entries.dump(2) << "\n";
    std::vector<const render::Image*> samples, errors;
    for (const SettingResult& r : results) {
        samples.push_back(&r.sample);
        if (!r.error.empty()) errors.push_back(&r.error);
    }
    if (!writeSvgPlot((out / "error_vs_time.svg").string(),
                      "image error against frame time (" + path.name + ")",
                      "frame time / all-LOD4 frame time (same run)", "mean PSNR against all-LOD4 (dB)",
                      {lodCurve, forcedPoints}, error) ||
        !render::writePng((out / "contact_sheet.png").string(), sideBySide(samples, 4), error) ||
        (!errors.empty() &&
         !render::writePng((out / "error_sheet.png").string(), sideBySide(errors, 4), error))) {
        std::cerr << "hexlod bench error: " << error << "\n";
        return 1;
    }
    if (o.json) {
        std::printf("%s\n", entries.dump().c_str());
        return 0;
    }
    std::printf("%-22s %12s %8s %10s %8s %12s\n", "setting", "frame ms", "ratio", "PSNR dB", "SSIM",
                "triangles");
    for (const auto& e : entries) {
        std::printf("%-22s %12.1f %8.3f %10s %8.4f %12.0f\n", e["setting"].get<std::string>().c_str(),
                    e["median_frame_ms"].get<double>(), e["frame_time_ratio_to_reference"].get<double>(),
                    e["mean_psnr_db"].is_null()
                        ? "-"
                        : std::to_string(e["mean_psnr_db"].get<double>()).substr(0, 5).c_str(),
                    e["mean_ssim"].get<double>(), e["median_triangles"].get<double>());
    }
    std::printf(
        "(contact sheet, by rows: the settings above in order: %s; their differences to the reference, "
        "times 4: %s)\n",
        (out / "contact_sheet.png").string().c_str(), (out / "error_sheet.png").string().c_str());
    return 0;
}

} // namespace hexlod::apps
