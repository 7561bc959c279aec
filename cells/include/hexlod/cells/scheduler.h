// The batch scheduler (thesis §7.5.1): per frame, which cells a camera sees, whether each
// needs terminal sets or does with its extruded set, and which missing batches to generate
// first, within a budget, in the background or synchronously.
//
// Rules, per update():
// - A cell is visible when its bounds box meets the camera frustum (Frustum::intersectsBox).
// - Every cell's LOD follows the screen-space error of its extruded set in the 3D Tiles way:
//   sse = lod.geometricError[1] * viewportHeight / (distance * 2 * tan(fovY / 2)), with distance
//   from the camera to the nearest point of the cell's bounds box (0 inside it: Terminals).
//   When that error would show (sse above lod.maxScreenSpaceError) the cell needs its terminal
//   sets. A hysteresis band keeps a hovering camera from thrashing: Extruded becomes Terminals
//   above maxSSE * (1 + hysteresis), Terminals becomes Extruded below maxSSE * (1 - hysteresis),
//   and in between a cell keeps its previous LOD (every cell starts Extruded).
// - forcedLod, when set, replaces that choice for every cell. Tree batches of a cell whose
//   trees would be acceptable as billboards (treeGeometricError) are left out of it.
// - Missing batches (not resident in the cache, not being generated) of visible Terminals cells
//   are queued by sse, highest first. Then come prefetch requests: the camera position is
//   extrapolated by its velocity (from the previous update) over prefetchSeconds, and the
//   batches of cells that would be visible and switch to Terminals there are queued by their
//   predicted sse, as are the tree batches of visible Terminals cells whose trees are
//   billboards now but would be wanted there. No other cell is ever generated.
// - At most maxBatchesPerFrame queued batches start per update (0: no cap), and none once
//   maxMillisecondsPerFrame has passed since update() began (0: no time budget), though the
//   first always starts so that a tiny budget still makes progress.
// - workers == 0: the started batches are generated inside update(), in queue order, so with no
//   time budget a scripted camera gives the same decisions every run. workers > 0: they go to a
//   pool of that many threads, each generating through the cache's getOrGenerate; update()
//   never waits for them, and their sets show as ready in a later frame. To keep priorities
//   fresh while the camera moves, no more than 2 * workers batches are in flight at once.
// - workers == 0 with prefetchInBackground: visible batches are made ready inside update() as
//   above, but prefetch requests go to one background thread (at most 2 in flight, at idle
//   priority), which reads them from the disk tier or generates them while frames render, on
//   the cores the frames leave idle. A visible batch the thread has in hand is waited for,
//   not left pending, so a scripted camera still sees the same cells ready in every frame;
//   only where the time goes changes.
//
// - onBackgroundSet, when set, is called on the background thread that read or generated a
//   set, once the cache holds it, with the set and its key's digest: work each frame would
//   otherwise do on a new set (the renderer's page bounds) is done there, off the frame.
//
// Readiness is checked with TerminalSetCache::find, which also marks visible sets as recently
// used, so the LRU evicts what the camera no longer looks at first. A batch whose generation
// threw is not requested again (failedBatches counts them).
//
// The catalog and the cache must outlive the scheduler. Edits (BatchCatalog::setParams) are
// safe between updates: a batch's inputs are copied when it starts, under its key then.
#pragma once

#include "hexlod/cells/batch_catalog.h"
#include "hexlod/scene/scene_config.h"

#include <glm/vec3.hpp>

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <unordered_set>
#include <vector>

namespace hexlod::cells {

struct Camera {
    glm::dvec3 position{0.0}, forward{0.0, 1.0, 0.0}, up{0.0, 0.0, 1.0};
    double fovY = 1.0; // radians
    uint32_t viewportWidth = 1920, viewportHeight = 1080;
    double nearPlane = 0.5, farPlane = 20000.0;
};

enum class CellLod : uint8_t { Extruded, Terminals };

struct SchedulerOptions {
    scene::LodProfile lod;
    uint32_t maxBatchesPerFrame = 8; // 0: no cap
    double maxMillisecondsPerFrame = 0.0;
    uint32_t workers = 0;
    // How far ahead the prefetch looks. At 1 s the walks' frames still waited for sets the
    // prefetch had not read yet (docs/BENCHMARKS.md, "The prefetch looks three seconds ahead");
    // at 5 s the rooftop flight read sets it never drew.
    double prefetchSeconds = 3.0;
    // workers == 0 only: prefetch on a background thread (see above); ignored with workers.
    bool prefetchInBackground = false;
    // Every cell takes this LOD whatever its error: the all-LOD4 reference and the forced-LOD
    // renders of the error reports.
    std::optional<CellLod> forcedLod;
    // Tree batches of a Terminals cell are wanted only while a tree drawn as its billboard,
    // of this geometric error (metres), would show (sse above maxScreenSpaceError; 0: always):
    // further away trees are billboards, and their terminal sets (most of a city's terminals)
    // are neither generated nor drawn.
    double treeGeometricError = 0.0;
    // Called on a background thread (workers, or the prefetch thread) after it read or
    // generated a set (see above); it must not throw. Never called from update().
    std::function<void(uint64_t keyDigest, const std::shared_ptr<const grammar::TerminalSet>& set)>
        onBackgroundSet;
};

struct CellDecision {
    HexCoord cell;
    double distance = 0.0; // metres, camera to the nearest point of the bounds box
    double sse = 0.0;      // pixels, of the extruded set
    CellLod lod = CellLod::Extruded;
    std::vector<uint32_t> ready;     // Terminals only: batches resident in the cache
    std::vector<uint32_t> requested; // Terminals only: the other batches (queued or generating)
    bool treesAsTerminals = false;   // its trees are wanted as terminals (see treeGeometricError)
};

struct FrameDecision {
    std::vector<CellDecision> cells; // visible cells, sorted by (q, r)
    std::vector<uint32_t> started;   // batches started this frame, in priority order
    uint32_t prefetchStarted = 0;    // how many of `started` were prefetch requests
    uint32_t terminalCells = 0;
    uint32_t readyBatches = 0;
    uint32_t requestedBatches = 0; // of visible Terminals cells
    uint32_t prefetchRequests = 0; // missing batches of predicted cells, started or not
    uint32_t inFlight = 0;         // batches queued or generating in the background after the update
    // prefetchInBackground: the sets of every cell's ready batches, held while the decision is,
    // so that the background thread's inserts cannot evict them before the frame draws them.
    std::vector<std::shared_ptr<const grammar::TerminalSet>> readySets;
};

class Scheduler {
public:
    // Throws std::invalid_argument for a non-positive maxScreenSpaceError or geometric error,
    // a hysteresis outside [0, 1), or a negative time budget or prefetch time.
    Scheduler(BatchCatalog& catalog, cache::TerminalSetCache& cache, SchedulerOptions options);
    ~Scheduler();
    Scheduler(const Scheduler&) = delete;
    Scheduler& operator=(const Scheduler&) = delete;

    // Throws std::invalid_argument for a camera the frustum rejects (see Frustum) or a zero
    // viewport.
    FrameDecision update(const Camera& camera, double timeSeconds);

    // Blocks until every started batch has finished; for tests and shutdown.
    void drain();
    uint64_t generatedBatches() const; // finished generations, failed ones included
    uint64_t failedBatches() const;

private:
    struct Request {
        uint32_t batch = 0;
        double sse = 0.0;
        bool prefetch = false;
    };
    struct Job {
        uint32_t batch = 0;
        cache::BatchKey key;
        std::vector<grammar::BuildingInput> inputs;
    };

    CellLod nextLod(CellLod previous, double sse) const;
    bool isTreeBatch(uint32_t batch) const;
    bool wantsTrees(double distance, const Camera& camera) const;
    double screenSpaceError(double distance, const Camera& camera) const;
    // Queues the batch unless the cache holds it; true when it does.
    bool requestIfMissing(uint32_t batch, double sse, bool prefetch, std::vector<Request>& queue,
                          FrameDecision& frame);
    bool prefetchThread() const; // workers == 0 with prefetchInBackground
    uint32_t backgroundThreads() const;
    // Whether update() itself reads or generates `request` (else a background thread does).
    bool inUpdate(const Request& request) const;
    void run(Job job);
    void workerLoop();

    BatchCatalog& catalog_;
    cache::TerminalSetCache& cache_;
    SchedulerOptions options_;
    std::vector<CellLod> lod_; // per cell of the index, in its order
    std::optional<glm::dvec3> lastPosition_;
    double lastTime_ = 0.0;

    mutable std::mutex mutex_; // guards everything below
    std::condition_variable wake_, idle_;
    std::deque<Job> jobs_;
    std::unordered_set<uint64_t> inFlight_; // key digests queued or generating
    std::unordered_set<uint64_t> failed_;
    uint64_t generated_ = 0, failedCount_ = 0;
    bool stopping_ = false;
    std::vector<std::thread> threads_;
};

} // namespace hexlod::cells
