// `hexlod bench error`: error against run time (ARCHITECTURE.md §8). The same camera path is
// rendered with every object at LOD4 (the reference), with the LOD system at a sweep of
// maxScreenSpaceError values, and with each LOD forced on everything; every frame is compared
// with the reference (PSNR, SSIM) next to its frame time and memory, times as ratios to the
// reference measured in the same run.
#pragma once

#include "render_options.h"

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace hexlod::apps {

struct BenchErrorOptions {
    std::string scenePath, pathPath, outDir;
    uint32_t frames = 24;
    std::vector<double> sse{0.5, 1, 2, 4, 8, 16};
    bool forced = true; // also the forced LOD3, LOD2, LOD1, LOD0 renders
    bool json = false;
    // Above 1: errors are measured against the all-LOD4 render at this many times the width
    // and height, box-filtered down (the timed reference stays at the target size).
    uint32_t referenceSupersample = 1;
    bool keepHidden = false; // every setting draws what the occluders hide (CityRendererOptions::dropHidden)
    // Timed passes over the path per setting: a frame's time is the median of its passes, so
    // that a burst of other work on the machine moves no ratio.
    uint32_t repeats = 3;
    RenderOptions render;
};

void registerBenchErrorCommand(CLI::App& bench, BenchErrorOptions& options, CLI::App*& command);
int runBenchErrorCommand(const BenchErrorOptions& options);

} // namespace hexlod::apps
