#include "walk_report.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <numeric>

namespace hexlod::apps {

double percentile(std::vector<double> values, double q) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    return values[size_t(std::lround(q * double(values.size() - 1)))];
}

double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

namespace {

nlohmann::json passJson(const std::function<double(lod::DrawPass)>& ms) {
    nlohmann::json passes = nlohmann::json::object();
    for (size_t p = 0; p < size_t(lod::DrawPass::Count); ++p)
        passes[lod::drawPassName(lod::DrawPass(p))] = ms(lod::DrawPass(p));
    return passes;
}

} // namespace

nlohmann::json frameJson(const lod::FrameStats& f) {
    return {
        {"frame", f.frame},
        {"frame_ms", f.frameMs},
        {"schedule_ms", f.scheduleMs},
        {"generation_ms", f.generationMs},
        {"disk_load_ms", f.diskLoadMs},
        {"disk_store_ms", f.diskStoreMs},
        {"upload_ms", f.uploadMs},
        {"cull_ms", f.cullMs},
        {"draw_ms", f.drawMs},
        {"gpu_wait_ms", f.gpuWaitMs},
        {"pass_ms", passJson([&](lod::DrawPass p) { return f.passMs[size_t(p)]; })},
        {"triangles", f.triangles},
        {"draws", f.draws},
        {"terminals_per_lod",
         {{"lod2", f.terminalsPerLod[2]}, {"lod3", f.terminalsPerLod[3]}, {"lod4", f.terminalsPerLod[4]}}},
        {"lod4_coarse_terminals", f.coarseTerminals},
        {"cells_per_lod",
         {{"lod0", f.cellsPerLod[0]}, {"lod1", f.cellsPerLod[1]}, {"terminal_sets", f.cellsPerLod[4]}}},
        {"visible_cells", f.visibleCells},
        {"cull_terminals", f.cullTerminals},
        {"cull_skipped_terminals", f.cullSkippedTerminals},
        {"cull_occluded_terminals", f.cullOccludedTerminals},
        {"cull_facing_away_terminals", f.cullFacingAwayTerminals},
        {"cull_billboard_terminals", f.cullBillboardTerminals},
        {"volumes_occluded", f.volumesOccluded},
        {"volumes_built", f.volumesBuilt},
        {"volume_buildings_occluded", f.volumeBuildingsOccluded},
        {"volume_building_points", f.volumeBuildingPoints},
        {"volumes_shaded_at_mean", f.volumesShadedAtMean},
        {"batches_drawn", f.batchesDrawn},
        {"batches_pending", f.batchesPending},
        {"batches_rejected", f.batchesRejected},
        {"batches_uploaded", f.batchesUploaded},
        {"uploads_prepared", f.uploadsPrepared},
        {"cache_lookups", f.cacheLookups},
        {"cache_hits", f.cacheHits},
        {"tree_billboards", f.treeBillboards},
        {"tree_points", f.treePoints},
        {"tree_billboards_occluded", f.treeBillboardsOccluded},
        {"lod3_occluded", f.lod3Occluded},
        {"cache_bytes", f.cacheBytes},
        {"gpu_bytes", f.gpuBytes},
        {"volume_bytes", f.volumeBytes},
        {"impostor_bytes", f.impostorBytes},
        {"resident_bytes", f.residentBytes()}};
}

bool writeFramesCsv(const std::string& path, const std::vector<lod::FrameStats>& frames, std::string& error) {
    std::ofstream out(path);
    out << "frame,frame_ms,schedule_ms,generation_ms,upload_ms,cull_ms,draw_ms,gpu_wait_ms,triangles,draws,"
           "lod2_terminals,lod3_terminals,lod4_terminals,lod4_coarse_terminals,lod0_cells,lod1_cells,"
           "terminal_set_cells,visible_cells,cache_bytes,gpu_bytes,impostor_bytes,resident_bytes\n";
    for (const lod::FrameStats& f : frames) {
        out << f.frame << ',' << f.frameMs << ',' << f.scheduleMs << ',' << f.generationMs << ','
            << f.uploadMs << ',' << f.cullMs << ',' << f.drawMs << ',' << f.gpuWaitMs << ',' << f.triangles
            << ',' << f.draws << ',' << f.terminalsPerLod[2] << ',' << f.terminalsPerLod[3] << ','
            << f.terminalsPerLod[4] << ',' << f.coarseTerminals << ',' << f.cellsPerLod[0] << ','
            << f.cellsPerLod[1] << ',' << f.cellsPerLod[4] << ',' << f.visibleCells << ',' << f.cacheBytes
            << ',' << f.gpuBytes << ',' << f.impostorBytes << ',' << f.residentBytes() << '\n';
    }
    if (!out) {
        error = path + ": cannot write";
        return false;
    }
    return true;
}

nlohmann::json summarizeFrames(const std::vector<lod::FrameStats>& frames) {
    auto column = [&](const std::function<double(const lod::FrameStats&)>& get) {
        std::vector<double> values;
        for (const lod::FrameStats& f : frames) values.push_back(get(f));
        return values;
    };
    uint64_t peak = 0, peakCache = 0, lookups = 0, hits = 0;
    for (const lod::FrameStats& f : frames) {
        peak = std::max(peak, f.residentBytes());
        peakCache = std::max(peakCache, f.cacheBytes);
        lookups += f.cacheLookups;
        hits += f.cacheHits;
    }
    const auto generationMs = column([](const auto& f) { return f.generationMs; });
    const auto frameMs = column([](const auto& f) { return f.frameMs; });
    return {
        {"frames", frames.size()},
        {"median_frame_ms", median(frameMs)},
        {"p95_frame_ms", percentile(frameMs, 0.95)},
        {"median_triangles", median(column([](const auto& f) { return double(f.triangles); }))},
        {"median_draws", median(column([](const auto& f) { return double(f.draws); }))},
        // Terminal sets in view that the GPU arena could not hold, drawn at LOD1 or LOD0.
        {"median_batches_rejected", median(column([](const auto& f) { return double(f.batchesRejected); }))},
        {"terminals_per_lod",
         {{"lod2", median(column([](const auto& f) { return double(f.terminalsPerLod[2]); }))},
          {"lod3", median(column([](const auto& f) { return double(f.terminalsPerLod[3]); }))},
          {"lod4", median(column([](const auto& f) { return double(f.terminalsPerLod[4]); }))}}},
        {"cells_per_lod",
         {{"lod0", median(column([](const auto& f) { return double(f.cellsPerLod[0]); }))},
          {"lod1", median(column([](const auto& f) { return double(f.cellsPerLod[1]); }))},
          {"terminal_sets", median(column([](const auto& f) { return double(f.cellsPerLod[4]); }))}}},
        {"median_stage_ms",
         {{"schedule", median(column([](const auto& f) { return f.scheduleMs; }))},
          {"upload", median(column([](const auto& f) { return f.uploadMs; }))},
          {"cull", median(column([](const auto& f) { return f.cullMs; }))},
          {"draw", median(column([](const auto& f) { return f.drawMs; }))},
          {"gpu_wait", median(column([](const auto& f) { return f.gpuWaitMs; }))}}},
        // With --time-passes: the draw stage split by pass, GL time included.
        {"median_pass_ms", passJson([&](lod::DrawPass p) {
             return median(column([p](const auto& f) { return f.passMs[size_t(p)]; }));
         })},
        {"total_generation_ms", std::accumulate(generationMs.begin(), generationMs.end(), 0.0)},
        {"median_generation_ms", median(generationMs)},
        {"p95_generation_ms", percentile(generationMs, 0.95)},
        {"median_disk_load_ms", median(column([](const auto& f) { return f.diskLoadMs; }))},
        {"median_disk_store_ms", median(column([](const auto& f) { return f.diskStoreMs; }))},
        // Of the scheduler's cache lookups over the walk: how often a batch it wanted was ready.
        {"cache_lookups", lookups},
        {"cache_hit_rate",
         lookups ? nlohmann::json(double(hits) / double(lookups)) : nlohmann::json(nullptr)},
        {"peak_cache_bytes", peakCache},
        {"peak_resident_bytes", peak}};
}

} // namespace hexlod::apps
