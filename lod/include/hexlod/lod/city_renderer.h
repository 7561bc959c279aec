// One frame of the city (thesis §7.3-7.5; ARCHITECTURE.md §5, §6), in order:
//   1. per cell on the CPU: frustum culling and the cell's LOD (terminal set or extruded set)
//      through the scheduler, which also generates the batches a frame needs;
//   2. upload: newly ready terminal sets into the paged terminal arena;
//   3. one compute pass over every terminal of the resident batches in view: frustum and
//      backface culling, LOD4/LOD3/LOD2 by screen-space error, compacted draw lists;
//   4. draws: LOD4 meshes instanced from the lists (per-instance attributes), LOD3/LOD2
//      impostor boxes ray-cast into their shapes' views, base volumes (LOD0 with a wall
//      texture; plain shells under terminals).
// Everything is camera-relative: cell origins minus the camera are taken in double and only
// then rounded to float. Depth is reversed-Z in a float buffer, so near 1e-4 m and far 1e7 m
// keep their precision. Needs a current GL context.
#pragma once

#include "hexlod/cache/terminal_set_cache.h"
#include "hexlod/cells/scheduler.h"
#include "hexlod/impostor/impostor_textures.h"
#include "hexlod/lod/building_points.h"
#include "hexlod/lod/depth_tiles.h"
#include "hexlod/lod/draw_pass.h"
#include "hexlod/lod/gpu_cull.h"
#include "hexlod/lod/ground_pass.h"
#include "hexlod/lod/occlusion_tests.h"
#include "hexlod/lod/prepared_page_bounds.h"
#include "hexlod/lod/quad_indices.h"
#include "hexlod/lod/scene_impostors.h"
#include "hexlod/lod/shape_table.h"
#include "hexlod/lod/terminal_arena.h"
#include "hexlod/lod/tree_pass.h"
#include "hexlod/lod/volume_cache.h"
#include "hexlod/render/framebuffer.h"
#include "hexlod/scene/camera_path.h"

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace hexlod::lod {

// Lod: the LOD system. The others force one LOD on everything in view, for the error reports;
// AllLod4 is their reference.
enum class RenderMode : uint8_t { Lod, AllLod4, AllLod3, AllLod2, AllLod1, AllLod0 };
const char* renderModeName(RenderMode mode); // "lod", "lod4", "lod3", ...
bool parseRenderMode(std::string_view name, RenderMode& out);

struct CityRendererOptions {
    uint32_t width = 1280, height = 720;
    // Samples per pixel (multisampling, alpha to coverage for impostors): what a viewer sees
    // at a silhouette, and what image errors should be measured on.
    uint32_t samples = 1;
    RenderMode mode = RenderMode::Lod;
    scene::LodProfile lod;
    uint64_t arenaRecords = uint64_t(1) << 23;        // 8 M terminals, 256 MiB, if the GL allows
    uint64_t volumeBudgetBytes = uint64_t(256) << 20; // base volume meshes
    double transitionBand = 0.15;                     // share of each LOD's range that blends into the next
    uint32_t parallaxIterations = 2;                  // LOD3
    // 0: visible batches are read or generated in the frame that needs them, so every frame is
    // complete and the same each run; the prefetch ahead of the camera runs on a thread beside
    // the frames (SchedulerOptions::prefetchInBackground).
    uint32_t schedulerWorkers = 0;
    uint32_t maxBatchesPerFrame = 0; // 0: no cap
    // Times every draw pass (FrameStats::passMs): where a frame's GL time goes. GL timestamps
    // where they time the GPU's work (GlContextInfo::gpuTimestamps); else glFinish after each
    // pass and the wall clock, which costs a tiled rasteriser its overlap between passes.
    PassClock passClock = PassClock::Off;
    // Culls terminals, and drops LOD3 impostors and tree billboards whole, that the depth drawn
    // before them hides (DepthTiles). Off only to check that it changes no pixel.
    bool dropHidden = true;
    // A far tree is a point (tree_point.vert) when its sphere's diameter on screen is under this
    // many times the profile's maxScreenSpaceError: its billboard would show no detail the bound
    // admits. 0: never.
    double treePointsUnderSse = 2.0;
    // A building of a batch drawn at LOD0 is a point (building_points.h) when its box's bounding
    // sphere is smaller on screen than this many times the profile's maxScreenSpaceError, the
    // trees' rule. 0: never.
    double buildingPointsUnderSse = 2.0;
    // Each tree billboard covers its species' box on screen rather than its bounding sphere's
    // square, where the impostor can show nothing. Off only to check that it changes no pixel.
    bool fitTreeBillboards = true;
    // LOD0 batches beyond the depth where the wall texture is its mean are shaded with that
    // mean per vertex (wall_texture_mean.h). Off only to check that it changes no pixel.
    bool shadeFarWallsAtMean = true;
};

struct FrameStats {
    uint64_t frame = 0;
    // CPU milliseconds per stage; frameMs is the whole frame's wall time, GPU work included
    // (timer queries read 0 on llvmpipe, so the frame ends with glFinish).
    double scheduleMs = 0.0, generationMs = 0.0, uploadMs = 0.0, cullMs = 0.0, drawMs = 0.0, gpuWaitMs = 0.0,
           frameMs = 0.0;
    // The cache's disk tier from the frame's start to its end, on any thread: reading and
    // decoding evicted sets back (on the frame's thread without workers, part of scheduleMs),
    // encoding and writing new ones (on the cache's writer thread, alongside the frame).
    double diskLoadMs = 0.0, diskStoreMs = 0.0;
    uint64_t triangles = 0, draws = 0;
    std::array<uint64_t, 5> terminalsPerLod{}; // LOD2..LOD4 drawn terminals (0 and 1 unused)
    uint64_t coarseTerminals = 0;              // of the LOD4 ones, drawn with a coarse mesh
    std::array<uint32_t, 5> cellsPerLod{};     // cells in view: 0 and 1 extruded, 4 with terminal sets
    // Terminals of the batches drawn: culled one by one on the GPU, or skipped with their
    // arena page, whose bounds lie outside the frustum or behind the occlusion tiles, or face
    // away, or whose trees are all billboards (the last two counted apart too).
    uint64_t cullTerminals = 0, cullSkippedTerminals = 0, cullFacingAwayTerminals = 0,
             cullBillboardTerminals = 0;
    // Terminals the base volumes and ground hide: skipped with their page, or culled one by one.
    uint64_t cullOccludedTerminals = 0;
    // Batches of base volumes of extruded cells not drawn (nor built, when not resident): the
    // nearer volumes' depth hides their box. volumesBuilt: base volume meshes built this frame.
    uint32_t volumesOccluded = 0, volumesBuilt = 0;
    // Buildings of the batches drawn at LOD0 or LOD1 left out: the nearer volumes hide their box.
    uint32_t volumeBuildingsOccluded = 0;
    // Buildings of the batches drawn at LOD0 drawn as points (building_points.h), not meshes.
    uint32_t volumeBuildingPoints = 0;
    // Batches drawn at LOD0 whose wall texture is its mean, shaded so (wall_texture_mean.h).
    uint32_t volumesShadedAtMean = 0;
    uint32_t visibleCells = 0, batchesDrawn = 0, batchesPending = 0, batchesRejected = 0;
    // Batches uploaded to the arena this frame, and of those, the ones whose page bounds were
    // prepared off the frame (PreparedPageBounds).
    uint32_t batchesUploaded = 0, uploadsPrepared = 0;
    uint32_t treeBillboards = 0;              // submitted (near ones are dropped on the GPU)
    uint32_t treePoints = 0;                  // far trees submitted to the point pass
    uint32_t treeBillboardsOccluded = 0;      // of those, dropped whole as hidden (DepthTiles)
    uint32_t lod3Occluded = 0;                // LOD3 and LOD3-LOD2 entries dropped as hidden
    uint64_t cacheLookups = 0, cacheHits = 0; // this frame's
    uint64_t cacheBytes = 0;                  // terminal sets in the cache's memory tier
    // The arena (and its page tables, on the CPU, prepared ones included), draw lists, meshes,
    // base volumes, frame target.
    uint64_t gpuBytes = 0;
    uint64_t volumeBytes = 0;   // of gpuBytes, the base volumes resident (VolumeCache)
    uint64_t impostorBytes = 0; // impostor textures
    // GL milliseconds per draw pass, with CityRendererOptions::passClock; 0 otherwise.
    PassTimes passMs{};
    uint64_t residentBytes() const { return cacheBytes + gpuBytes + impostorBytes; }
};

class CityRenderer {
public:
    // `impostors` may be null (no impostors: every terminal draws at LOD4). The catalog, cache,
    // meshes and impostors must outlive the renderer.
    CityRenderer(cells::BatchCatalog& catalog, cache::TerminalSetCache& cache,
                 const render::TerminalMeshLibrary& meshes, const SceneImpostors* impostors,
                 CityRendererOptions options);
    ~CityRenderer();

    bool init(std::string& error);
    FrameStats render(const scene::CameraPose& pose, double timeSeconds, double nearPlane, double farPlane);
    render::Image readColor() const { return target_.readColor(0); }
    const CityRendererOptions& options() const { return options_; }
    // What the renderer compiled: "LOD1 shaders: 2 grammars".
    std::string summary() const;
    // The coarse meshes the LOD system may draw (describeCoarseMeshes); empty without any.
    const std::string& coarseNote() const { return coarseNote_; }
    // "terminal arena: 4.19 M records, capped by the GL (...)" when the GL holds fewer
    // terminals on the GPU than the options ask for; empty otherwise.
    std::string arenaNote() const;
    // GPU bytes of the tree billboards (positions, species, impostors): 0 without trees.
    uint64_t treeBytes() const { return trees_.byteSize(); }

private:
    struct Programs;
    struct VolumeDraw {
        // Null until the batch is known to be drawn: beyond the first ring a batch is built
        // only when the rings before it leave it a chance to show.
        const VolumeMesh* mesh;
        uint32_t batch;
        float inset;     // VolumeCache::acquire's
        bool textured;   // LOD0's wall texture (not under terminals)
        float lod0Blend; // 1: LOD0; below 1: LOD1, blending into LOD0
        // Drawn nearest ring first: 0, under terminal sets; 1, extruded cells within LOD1's
        // distance; 2, beyond it. A ring draws only the batches whose box (the mesh's bounds
        // when it is resident, else the cell's) the depth of the rings before it does not hide.
        uint8_t ring;
        // Set by drawVolumeRings: the runs (first index, count) of the mesh to draw, the whole
        // mesh or its buildings left in view by the rings before, adjacent ones merged; and the
        // runs (first building, count) of those drawn as points.
        std::vector<glm::uvec2> runs = {};
        std::vector<glm::uvec2> pointRuns = {};
    };
    static constexpr uint8_t kVolumeRings = 3;
    void drawTerminalMeshes(PassTimer& timer); // LOD4 meshes
    // Every terminal the cull sent to each LOD, into stats (waits for the cull).
    void countCulledTerminals(FrameStats& stats);
    // Whether the cull may send terminals to impostors: there are some, and the mode allows it.
    bool impostorsDrawn() const {
        return impostorTextures_.layers() > 0 && options_.mode != RenderMode::AllLod4;
    }
    // LOD2 and LOD3; LOD3 ray-casts from the unprojected screen (inverseViewProjection).
    // Returns whether it drew them, building the depth tiles after LOD4 and LOD2 for LOD3.
    bool drawImpostors(const glm::mat4& inverseViewProjection, PassTimer& timer);
    // The base volumes ring by ring, each against the depth tiles of the rings before it: at
    // street level most of the city stands behind the street's walls.
    void drawVolumeRings(const std::vector<VolumeDraw>& volumes, const scene::CameraPose& pose,
                         double nearPlane, double farPlane, FrameStats& stats, PassTimer& timer);
    // Whether the tiles hide the batch's box: its mesh's bounds when resident, else its cell's.
    bool volumeHidden(const VolumeDraw& draw, const glm::dvec3& camera, const shared::CullFrame& occlusion,
                      const OcclusionGrid& tiles) const;
    // Sets draw.runs and draw.pointRuns to draw.mesh's buildings the tiles leave in view (null
    // tiles: all of them; none: all hidden), within LOD1's distance nearest first
    // (building_order.h); at LOD0, those `cut` makes points as points. Counts the hidden ones
    // and the points into stats.
    void selectBuildingRuns(VolumeDraw& draw, const glm::dvec3& camera, const shared::CullFrame& occlusion,
                            const OcclusionGrid* tiles, const BuildingPointCut& cut, FrameStats& stats) const;
    // LOD0's buildings drawn as points, after their batches' meshes.
    void drawBuildingPoints(const std::vector<VolumeDraw>& volumes, const glm::dvec3& camera,
                            float screenScale, FrameStats& stats);
    void drawVolumes(const std::vector<VolumeDraw>& volumes, const scene::CameraPose& pose, float screenScale,
                     FrameStats& stats, PassTimer& timer);
    static void drawRuns(const VolumeDraw& draw, FrameStats& stats);

    cells::BatchCatalog& catalog_;
    cache::TerminalSetCache& cache_;
    const render::TerminalMeshLibrary& meshes_;
    const SceneImpostors* impostors_;
    CityRendererOptions options_;
    // Filled by the scheduler's background thread, so it is shared with the scheduler's hook.
    std::shared_ptr<PreparedPageBounds> preparedBounds_ = std::make_shared<PreparedPageBounds>();
    std::unique_ptr<cells::Scheduler> scheduler_;
    std::unique_ptr<Programs> programs_;
    render::Framebuffer target_;
    TerminalArena arena_;
    GpuCull cull_;
    ShapeTable shapes_;
    VolumeCache volumes_;
    GroundPass ground_;
    TreePass trees_;
    DepthTiles depthTiles_;     // for the cull, LOD3 impostors and tree billboards
    DepthTiles volumeTiles_;    // finer, for the base volume rings' CPU tests
    QuadIndices impostorQuads_; // the impostor passes' index buffer
    double treeError_ = 0.0;    // metres; 0: trees are always geometry
    impostor::ImpostorTextures impostorTextures_;
    uint32_t sphereBuffer_ = 0, frameBuffer_ = 0, lod4Vao_ = 0, impostorVao_ = 0;
    uint32_t centralView_ = 0;
    std::vector<uint8_t> shapeTree_; // per global shape: part of a tree
    std::string coarseNote_;         // describeCoarseMeshes, for summary()
    uint64_t frame_ = 0;
};

} // namespace hexlod::lod
