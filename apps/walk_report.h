// Per-frame statistics of a walkthrough as JSON and CSV, and their summary (medians and
// 95th percentiles, peak memory), the shape `hexlod walk --json` and the benchmarks print.
#pragma once

#include "hexlod/lod/city_renderer.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace hexlod::apps {

nlohmann::json frameJson(const lod::FrameStats& frame);
bool writeFramesCsv(const std::string& path, const std::vector<lod::FrameStats>& frames, std::string& error);

// frames, median_frame_ms, p95_frame_ms, median_triangles, terminals_per_lod (medians),
// cells_per_lod (medians), peak_resident_bytes, median stage times and generation ms.
nlohmann::json summarizeFrames(const std::vector<lod::FrameStats>& frames);

double median(std::vector<double> values);
double percentile(std::vector<double> values, double q);

} // namespace hexlod::apps
