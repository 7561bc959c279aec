// Scheduler decisions for scripted cameras on a small procedural city: which cells are seen,
// at which LOD, in which order their batches are generated, that the hysteresis holds, that
// prefetch runs ahead of a moving camera (on a thread of its own too, changing no frame), that
// a worker pool never blocks update(), and that the cache keeps its byte budget over a walk.
#include "hexlod/cells/scheduler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>
#include <set>
#include <thread>

namespace hexlod::cells {

scene::BuiltScene smallCity(); // batch_catalog_test.cpp

namespace {

using Clock = std::chrono::steady_clock;

// Default profile: geometric error 4 m at 1080 pixels and fovY 1 rad switches to Terminals
// closer than about 1,647 m and back beyond about 2,471 m.
SchedulerOptions options(uint32_t maxBatches, double prefetchSeconds = 0.0, uint32_t workers = 0) {
    SchedulerOptions o;
    o.maxBatchesPerFrame = maxBatches;
    o.prefetchSeconds = prefetchSeconds;
    o.workers = workers;
    return o;
}

double switchUpDistance(const SchedulerOptions& o, const Camera& c) {
    return o.lod.geometricError[1] * c.viewportHeight /
           (2.0 * std::tan(c.fovY * 0.5) * o.lod.maxScreenSpaceError * (1.0 + o.lod.hysteresis));
}

class SchedulerTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() { scene_ = new scene::BuiltScene(smallCity()); }
    static void TearDownTestSuite() { delete scene_; }

    // A camera `d` metres south of `target`'s bounds box, level with its middle, looking north.
    Camera southOf(const CellBounds& target, double d) const {
        Camera c;
        c.position = {(target.lo.x + target.hi.x) * 0.5, target.lo.y - d, (target.zMin + target.zMax) * 0.5};
        c.forward = {0.0, 1.0, 0.0};
        return c;
    }
    // The occupied cell nearest the city's middle: the approach target.
    const CellBounds& middleCell() const {
        const auto cells = catalog_.index().cells();
        glm::dvec2 mean(0.0);
        for (const CellBounds& c : cells) mean += catalog_.index().grid().center(c.cell);
        mean /= static_cast<double>(cells.size());
        return *std::min_element(cells.begin(), cells.end(), [&](const CellBounds& a, const CellBounds& b) {
            return glm::distance(catalog_.index().grid().center(a.cell), mean) <
                   glm::distance(catalog_.index().grid().center(b.cell), mean);
        });
    }
    static const CellDecision* find(const FrameDecision& frame, HexCoord cell) {
        for (const CellDecision& c : frame.cells)
            if (c.cell == cell) return &c;
        return nullptr;
    }

    static scene::BuiltScene* scene_;
    BatchCatalog catalog_{*scene_};
    cache::TerminalSetCache cache_{cache::CacheOptions{}};
};
scene::BuiltScene* SchedulerTest::scene_ = nullptr;

TEST_F(SchedulerTest, AFarCameraSeesExtrudedCellsAndGeneratesNothing) {
    Scheduler scheduler(catalog_, cache_, options(8, 2.0));
    Camera camera = southOf(middleCell(), 6000.0);
    for (int frame = 0; frame < 5; ++frame) {
        const FrameDecision decision = scheduler.update(camera, frame * 0.1);
        EXPECT_GT(decision.cells.size(), 5u);
        for (const CellDecision& c : decision.cells) {
            EXPECT_EQ(c.lod, CellLod::Extruded);
            EXPECT_GT(c.distance, 5000.0);
            EXPECT_LT(c.sse, 1.0);
            EXPECT_TRUE(c.ready.empty() && c.requested.empty());
        }
        EXPECT_TRUE(decision.started.empty());
        camera.position.y += 1.0; // slow: the prediction stays far too
    }
    EXPECT_EQ(cache_.stats().generations, 0u);
    EXPECT_EQ(scheduler.generatedBatches(), 0u);
}

TEST_F(SchedulerTest, FlyingTowardACellSwitchesItAndGeneratesBySseWithinTheBudget) {
    const SchedulerOptions o = options(3);
    Scheduler scheduler(catalog_, cache_, o);
    const CellBounds& target = middleCell();
    Camera camera = southOf(target, 4000.0);
    const double switchAt = switchUpDistance(o, camera);
    bool switched = false;
    size_t started = 0;
    for (int frame = 0; frame < 60; ++frame) {
        const FrameDecision decision = scheduler.update(camera, frame * 0.5);
        const CellDecision* mine = find(decision, target.cell);
        ASSERT_NE(mine, nullptr);
        EXPECT_NEAR(mine->distance, std::max(4000.0 - 100.0 * frame, 0.0), 1e-6);
        EXPECT_EQ(mine->lod == CellLod::Terminals, mine->distance < switchAt) << "frame " << frame;
        switched = switched || mine->lod == CellLod::Terminals;

        EXPECT_LE(decision.started.size(), 3u);
        std::map<uint32_t, double> sseOf;
        for (const CellDecision& c : decision.cells)
            for (const uint32_t b : c.requested) sseOf[b] = c.sse;
        for (const CellDecision& c : decision.cells)
            for (const uint32_t b : c.ready) sseOf[b] = c.sse;
        for (size_t i = 0; i < decision.started.size(); ++i) {
            ASSERT_TRUE(sseOf.contains(decision.started[i])); // only visible Terminals cells
            if (i > 0) {
                EXPECT_GE(sseOf[decision.started[i - 1]], sseOf[decision.started[i]]);
            }
        }
        // Unstarted requests never outrank a started one.
        if (decision.started.size() == 3 && decision.requestedBatches > 0) {
            for (const CellDecision& c : decision.cells)
                for (const uint32_t b : c.requested) EXPECT_LE(sseOf[b], sseOf[decision.started.back()]);
        }
        started += decision.started.size();
        if (frame < 40) camera.position.y += 100.0;
    }
    EXPECT_TRUE(switched);
    EXPECT_GT(started, 3u);
    EXPECT_EQ(cache_.stats().generations, started);
    // Standing still for 20 frames finished every visible Terminals batch.
    const FrameDecision last = scheduler.update(camera, 100.0);
    EXPECT_TRUE(last.started.empty());
    EXPECT_EQ(last.requestedBatches, 0u);
    EXPECT_EQ(find(last, target.cell)->ready.size(), catalog_.index().batchesOf(target.cell).size());
}

TEST_F(SchedulerTest, HysteresisKeepsAHoveringCameraFromThrashing) {
    const CellBounds& target = middleCell();
    for (const double band : {0.2, 0.0}) {
        SchedulerOptions o = options(1);
        o.lod.hysteresis = band;
        cache::TerminalSetCache cache{cache::CacheOptions{}};
        Scheduler scheduler(catalog_, cache, o);
        const double switchAt = switchUpDistance(o, southOf(target, 0.0));
        int flips = 0;
        CellLod previous = CellLod::Extruded;
        for (int frame = 0; frame < 1000; ++frame) {
            const double d = switchAt + (frame % 2 == 0 ? -5.0 : 5.0);
            const FrameDecision decision = scheduler.update(southOf(target, d), frame / 60.0);
            const CellLod now = find(decision, target.cell)->lod;
            flips += now != previous;
            previous = now;
        }
        if (band > 0.0) {
            EXPECT_EQ(flips, 1);
        } else {
            EXPECT_EQ(flips, 1000); // without the band every step across the switch flips it
        }
    }
}

TEST_F(SchedulerTest, ACameraLookingAwayNeverGeneratesCellsBehindIt) {
    Scheduler scheduler(catalog_, cache_, options(0, 2.0));
    const CellBounds& middle = middleCell();
    Camera camera;
    camera.position = {(middle.lo.x + middle.hi.x) * 0.5, (middle.lo.y + middle.hi.y) * 0.5, 40.0};
    camera.forward = {0.0, 1.0, -0.2};
    const double startY = camera.position.y;
    for (int frame = 0; frame < 10; ++frame) {
        const FrameDecision decision = scheduler.update(camera, frame * 0.1);
        EXPECT_GT(decision.terminalCells, 0u);
        // Everything started is of a visible Terminals cell, or a prefetch.
        for (size_t i = 0; i < decision.started.size() - decision.prefetchStarted; ++i) {
            const CellDecision* c = find(decision, catalog_.batch(decision.started[i]).cell);
            ASSERT_NE(c, nullptr);
            EXPECT_EQ(c->lod, CellLod::Terminals);
        }
        camera.position.y += 5.0; // forward, so prefetch looks ahead too
    }
    size_t behind = 0, generated = 0;
    for (uint32_t b = 0; b < catalog_.batchCount(); ++b) {
        const CellBounds& bounds = *catalog_.index().boundsOf(catalog_.batch(b).cell);
        const bool cached = cache_.find(catalog_.key(b)) != nullptr;
        generated += cached;
        if (bounds.hi.y < startY - 60.0) { // wholly behind the eye from the first frame on
            ++behind;
            EXPECT_FALSE(cached) << "batch " << b << " behind the camera was generated";
        }
    }
    EXPECT_GT(behind, 5u);
    EXPECT_GT(generated, 0u);
}

TEST_F(SchedulerTest, PrefetchRequestsCellsAheadOfAMovingCamera) {
    const CellBounds& target = middleCell();
    const auto flipFrame = [&](double prefetchSeconds, bool& targetAlreadyCached) {
        cache::TerminalSetCache cache{cache::CacheOptions{}};
        Scheduler scheduler(catalog_, cache, options(0, prefetchSeconds));
        Camera camera = southOf(target, 3000.0);
        uint32_t prefetched = 0;
        for (int frame = 0; frame < 40; ++frame) {
            const uint32_t first = catalog_.firstBatchOf(target.cell);
            targetAlreadyCached = cache.find(catalog_.key(first)) != nullptr;
            const FrameDecision decision = scheduler.update(camera, frame * 1.0);
            for (size_t i = decision.started.size() - decision.prefetchStarted; i < decision.started.size();
                 ++i) {
                // A prefetched batch's cell is not (yet) visible at Terminals.
                const CellDecision* c = find(decision, catalog_.batch(decision.started[i]).cell);
                EXPECT_TRUE(c == nullptr || c->lod == CellLod::Extruded);
            }
            prefetched += decision.prefetchStarted;
            if (find(decision, target.cell)->lod == CellLod::Terminals) {
                if (prefetchSeconds > 0.0) {
                    EXPECT_GT(prefetched, 0u);
                }
                return frame;
            }
            camera.position.y += 100.0; // 100 m/s
        }
        return -1;
    };
    bool cachedWithout = true, cachedWith = false;
    const int without = flipFrame(0.0, cachedWithout);
    const int with = flipFrame(3.0, cachedWith);
    ASSERT_GE(without, 0);
    EXPECT_EQ(with, without); // prefetch changes what is generated, never the LOD
    EXPECT_FALSE(cachedWithout);
    EXPECT_TRUE(cachedWith); // ready before the cell needed it
}

TEST_F(SchedulerTest, TreesOfAVisibleCellArePrefetchedBeforeTheyAreWanted) {
    // A cell with trees: they are billboards (left out) until the camera is near.
    const size_t buildingGrammars = catalog_.scene().buildingGrammars.size();
    uint32_t treeBatch = catalog_.batchCount();
    for (uint32_t b = 0; b < catalog_.batchCount() && treeBatch == catalog_.batchCount(); ++b)
        if (catalog_.batch(b).grammar >= buildingGrammars) treeBatch = b;
    ASSERT_LT(treeBatch, catalog_.batchCount());
    const CellBounds& target = *catalog_.index().boundsOf(catalog_.batch(treeBatch).cell);
    const auto firstFrameWantingTrees = [&](double prefetchSeconds, bool& cachedBefore) {
        cache::TerminalSetCache cache{cache::CacheOptions{}};
        SchedulerOptions o = options(0, prefetchSeconds);
        o.treeGeometricError = 0.25; // trees wanted within about 120 m
        Scheduler scheduler(catalog_, cache, o);
        Camera camera = southOf(target, 600.0);
        for (int frame = 0; frame < 60; ++frame) {
            cachedBefore = cache.findInMemory(catalog_.key(treeBatch)) != nullptr;
            const FrameDecision decision = scheduler.update(camera, frame * 1.0);
            const CellDecision* cell = find(decision, target.cell);
            EXPECT_NE(cell, nullptr);
            if (cell && cell->treesAsTerminals) {
                EXPECT_EQ(cell->lod, CellLod::Terminals);
                return frame;
            }
            camera.position.y += 20.0; // 20 m/s
        }
        return -1;
    };
    bool cachedWithout = true, cachedWith = false;
    const int without = firstFrameWantingTrees(0.0, cachedWithout);
    const int with = firstFrameWantingTrees(3.0, cachedWith);
    ASSERT_GT(without, 0);
    EXPECT_EQ(with, without);
    EXPECT_FALSE(cachedWithout);
    EXPECT_TRUE(cachedWith); // read ahead while the cell drew its trees as billboards
}

TEST_F(SchedulerTest, APrefetchThreadChangesNoFrame) {
    const CellBounds& target = middleCell();
    cache::TerminalSetCache inFrameCache{cache::CacheOptions{}}, threadCache{cache::CacheOptions{}};
    Scheduler inFrame(catalog_, inFrameCache, options(0, 3.0));
    SchedulerOptions o = options(0, 3.0);
    o.prefetchInBackground = true;
    Scheduler withThread(catalog_, threadCache, o);
    Camera camera = southOf(target, 3000.0);
    uint32_t prefetchedByThread = 0;
    for (int frame = 0; frame < 40; ++frame) {
        const FrameDecision expected = inFrame.update(camera, frame * 1.0);
        const FrameDecision got = withThread.update(camera, frame * 1.0);
        EXPECT_TRUE(expected.readySets.empty());                  // only a prefetch thread's frames hold them
        EXPECT_EQ(got.requestedBatches, 0u) << "frame " << frame; // nothing visible left pending
        ASSERT_EQ(got.cells.size(), expected.cells.size()) << "frame " << frame;
        size_t ready = 0;
        for (size_t c = 0; c < got.cells.size(); ++c) {
            EXPECT_EQ(got.cells[c].cell, expected.cells[c].cell);
            EXPECT_EQ(got.cells[c].lod, expected.cells[c].lod);
            std::vector<uint32_t> a = got.cells[c].ready, b = expected.cells[c].ready;
            std::sort(a.begin(), a.end());
            std::sort(b.begin(), b.end());
            EXPECT_EQ(a, b) << "frame " << frame;
            for (const uint32_t batch : a) {
                // Each ready set is held by the decision: no insert can evict it meanwhile.
                const auto set = threadCache.findInMemory(catalog_.key(batch));
                ASSERT_NE(set, nullptr);
                EXPECT_NE(std::find(got.readySets.begin(), got.readySets.end(), set), got.readySets.end());
            }
            ready += a.size();
        }
        EXPECT_EQ(got.readySets.size(), ready);
        // What the thread was given is in the cache once it is done. Every other frame goes on
        // at once, so that visible batches the thread still holds are joined, not left pending.
        if (frame % 2 == 0) {
            withThread.drain();
            for (size_t i = got.started.size() - got.prefetchStarted; i < got.started.size(); ++i)
                EXPECT_NE(threadCache.findInMemory(catalog_.key(got.started[i])), nullptr);
        }
        prefetchedByThread += got.prefetchStarted;
        camera.position.y += 100.0;
    }
    EXPECT_GT(prefetchedByThread, 0u);
    withThread.drain();
    const cache::CacheStats stats = threadCache.stats();
    EXPECT_EQ(stats.generations, stats.memoryEntries); // each batch generated once, by one thread
}

// The hook sees every set a background thread read or generated, on that thread, as the cache
// holds it, and none that update() made ready itself.
TEST_F(SchedulerTest, BackgroundThreadsHandTheirSetsToTheHook) {
    const CellBounds& target = middleCell();
    for (const uint32_t workers : {0u, 2u}) {
        cache::TerminalSetCache cache{cache::CacheOptions{}};
        std::mutex mutex;
        std::map<uint64_t, std::shared_ptr<const grammar::TerminalSet>> handed;
        bool onUpdateThread = false;
        const std::thread::id updateThread = std::this_thread::get_id();
        SchedulerOptions o = options(0, 3.0, workers);
        o.prefetchInBackground = true;
        o.onBackgroundSet = [&](uint64_t key, const std::shared_ptr<const grammar::TerminalSet>& set) {
            std::lock_guard lock(mutex);
            onUpdateThread = onUpdateThread || std::this_thread::get_id() == updateThread;
            EXPECT_TRUE(handed.emplace(key, set).second) << "a set handed over twice";
        };
        Scheduler scheduler(catalog_, cache, o);
        Camera camera = southOf(target, 3000.0);
        std::set<uint32_t> background, inUpdate;
        for (int frame = 0; frame < 30; ++frame) {
            const FrameDecision decision = scheduler.update(camera, frame * 1.0);
            for (size_t i = 0; i < decision.started.size(); ++i) {
                // Without workers, the started batches before the prefetch ones were made ready
                // in update().
                const bool prefetch = i >= decision.started.size() - decision.prefetchStarted;
                (workers > 0 || prefetch ? background : inUpdate).insert(decision.started[i]);
            }
            scheduler.drain();
            camera.position.y += 100.0;
        }
        ASSERT_FALSE(background.empty()) << workers << " workers";
        std::lock_guard lock(mutex);
        EXPECT_FALSE(onUpdateThread);
        for (const uint32_t batch : background) {
            const auto it = handed.find(catalog_.key(batch).digest());
            ASSERT_NE(it, handed.end()) << "batch " << batch << ", " << workers << " workers";
            EXPECT_EQ(it->second, cache.findInMemory(catalog_.key(batch)));
        }
        for (const uint32_t batch : inUpdate) {
            if (!background.contains(batch)) {
                EXPECT_FALSE(handed.contains(catalog_.key(batch).digest()));
            }
        }
        EXPECT_EQ(handed.size(), background.size());
    }
}

TEST_F(SchedulerTest, WorkersGenerateInTheBackgroundWithoutBlockingUpdate) {
    // Towers make every business batch slow to expand, so blocking would show.
    ASSERT_TRUE(catalog_.setParams(GrammarName{"business"}, {{"floors", 120.0}}).ok);
    // The camera stands in the cell of the biggest business batch, whose sse puts it first.
    uint32_t biggest = 0;
    for (uint32_t b = 0; b < catalog_.batchCount(); ++b)
        if (catalog_.batch(b).grammar == 0 &&
            catalog_.batch(b).buildings.size() > catalog_.batch(biggest).buildings.size())
            biggest = b;
    const CellBounds& target = *catalog_.index().boundsOf(catalog_.batch(biggest).cell);
    const Camera camera = southOf(target, 0.0);
    Scheduler scheduler(catalog_, cache_, options(8, 0.0, 2));

    const auto begin = Clock::now();
    const FrameDecision first = scheduler.update(camera, 0.0);
    const double updateSeconds = std::chrono::duration<double>(Clock::now() - begin).count();
    ASSERT_FALSE(first.started.empty());
    // 2 * workers in flight at most; a worker that finishes during the update frees its slot,
    // so more may have started than are in flight.
    EXPECT_LE(first.inFlight, 4u);
    EXPECT_EQ(first.readyBatches, 0u);
    for (const uint32_t b : first.started) {
        const CellDecision* c = find(first, catalog_.batch(b).cell);
        ASSERT_NE(c, nullptr);
        EXPECT_NE(std::find(c->requested.begin(), c->requested.end(), b), c->requested.end());
    }

    scheduler.drain();
    EXPECT_EQ(scheduler.generatedBatches(), first.started.size());
    EXPECT_EQ(scheduler.failedBatches(), 0u);
    const FrameDecision second = scheduler.update(camera, 0.1);
    EXPECT_EQ(second.readyBatches, first.started.size());
    for (const uint32_t b : first.started)
        EXPECT_EQ(std::find(second.started.begin(), second.started.end(), b), second.started.end());

    double slowest = 0.0;
    for (const uint32_t b : first.started) {
        const auto t0 = Clock::now();
        const grammar::TerminalSet set = catalog_.generate(b);
        slowest = std::max(slowest, std::chrono::duration<double>(Clock::now() - t0).count());
    }
    // An update that waited for its workers would take at least the generation of the biggest
    // batch it started. The margin is that one generation, not a fraction of it: the other
    // tests of a parallel run share the two cores with this update and its workers.
    EXPECT_LT(updateSeconds, slowest) << "update " << updateSeconds << " s, generation " << slowest << " s";

    // Keep going until everything visible is ready; no frame waits.
    for (int frame = 2; frame < 200 && scheduler.update(camera, frame * 0.1).requestedBatches > 0; ++frame)
        scheduler.drain();
    EXPECT_EQ(scheduler.update(camera, 100.0).requestedBatches, 0u);
}

TEST_F(SchedulerTest, WithWorkersTheFrameLeavesDiskReadsToThem) {
    const std::filesystem::path folder =
        std::filesystem::path(::testing::TempDir()) / "hexlod-scheduler-disk";
    std::filesystem::remove_all(folder);
    // Memory keeps nothing unpinned: every set lives on disk once written.
    cache::TerminalSetCache disk(
        {.memoryBudgetBytes = 0, .diskBudgetBytes = uint64_t(1) << 30, .diskPath = folder.string()});
    const Camera camera = southOf(middleCell(), 0.0);
    {
        Scheduler generating(catalog_, disk, options(0));
        generating.update(camera, 0.0);
    }
    disk.flushDisk();
    const cache::CacheStats written = disk.stats();
    ASSERT_GT(written.diskFiles, 0u);

    // The update reads no file: every batch on disk is requested, not ready, and a worker reads
    // it back; none is generated again.
    Scheduler scheduler(catalog_, disk, options(0, 0.0, 1));
    const FrameDecision frame = scheduler.update(camera, 1.0);
    EXPECT_EQ(frame.readyBatches, 0u);
    ASSERT_FALSE(frame.started.empty());
    scheduler.drain();
    const cache::CacheStats read = disk.stats();
    EXPECT_EQ(read.diskHits - written.diskHits, frame.started.size());
    EXPECT_EQ(read.generations, written.generations);
    std::filesystem::remove_all(folder);
}

TEST_F(SchedulerTest, ATimeBudgetStartsOneBatchPerFrameWhenSpent) {
    SchedulerOptions o = options(0);
    o.maxMillisecondsPerFrame = 1e-9; // spent as soon as anything ran
    Scheduler scheduler(catalog_, cache_, o);
    const Camera camera = southOf(middleCell(), 0.0);
    const FrameDecision first = scheduler.update(camera, 0.0);
    EXPECT_EQ(first.started.size(), 1u);
    EXPECT_GT(first.requestedBatches, 0u);
    EXPECT_EQ(scheduler.update(camera, 0.1).started.size(), 1u);
    EXPECT_EQ(cache_.stats().generations, 2u);
}

TEST_F(SchedulerTest, TheCacheKeepsItsByteBudgetAcrossAWalk) {
    uint64_t total = 0;
    for (uint32_t b = 0; b < catalog_.batchCount(); ++b) total += catalog_.generate(b).byteSize();
    cache::CacheOptions small;
    small.memoryBudgetBytes = total / 6;
    cache::TerminalSetCache cache(small);
    Scheduler scheduler(catalog_, cache, options(4, 1.0));

    const auto cells = catalog_.index().cells();
    glm::dvec2 lo(1e300), hi(-1e300);
    for (const CellBounds& c : cells) lo = glm::min(lo, c.lo), hi = glm::max(hi, c.hi);
    Camera camera;
    camera.forward = {1.0, 0.0, -0.3};
    const int frames = 120;
    for (int frame = 0; frame < frames; ++frame) {
        const double t = frame / double(frames - 1);
        camera.position = {lo.x + t * (hi.x - lo.x), lo.y + (0.3 + 0.4 * t) * (hi.y - lo.y), 30.0};
        scheduler.update(camera, frame * 0.2);
        EXPECT_LE(cache.stats().memoryBytes, small.memoryBudgetBytes) << "frame " << frame;
    }
    const cache::CacheStats stats = cache.stats();
    EXPECT_GT(stats.generations, 10u);
    EXPECT_GT(stats.evictions, 0u);
    EXPECT_EQ(stats.pinnedBytes, 0u);
}

} // namespace
} // namespace hexlod::cells
