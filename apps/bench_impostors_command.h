// `hexlod bench impostors`: what an impostor's view grid costs and buys (thesis §7.3.1). For
// every facade shape the scene's buildings can emit and each grid size N of a sweep, the shape
// is baked on an N x N hemi-octahedral grid, its EXR and GPU bytes are counted, and the 4-view
// reconstruction (the LOD3 blend with parallax) at fixed directions between the views is
// compared with a direct render of the mesh from the same direction (PSNR over covered pixels).
// Writes a table (CSV, JSON) and the error against N and against bytes (SVG).
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

namespace hexlod::apps {

struct BenchImpostorsOptions {
    std::string scenePath, outDir, backend = "auto";
    std::vector<uint32_t> grids{2, 4, 8, 16, 32};
    uint32_t resolution = 32; // texels per view side
    uint32_t directions = 16; // compared directions per shape, within 60 degrees of the normal
    bool json = false;
};

void registerBenchImpostorsCommand(CLI::App& bench, BenchImpostorsOptions& options, CLI::App*& command);
int runBenchImpostorsCommand(const BenchImpostorsOptions& options);

} // namespace hexlod::apps
