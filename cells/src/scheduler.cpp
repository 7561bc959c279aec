#include "hexlod/cells/scheduler.h"

#include "hexlod/cells/frustum.h"

#include <glm/geometric.hpp>
#include <tbb/task_arena.h>

#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tuple>

namespace hexlod::cells {
namespace {

enum class Busy { No, Generating, Failed };

double distanceToBox(glm::dvec3 p, glm::dvec3 lo, glm::dvec3 hi) {
    const glm::dvec3 outside = glm::max(glm::max(lo - p, p - hi), glm::dvec3(0.0));
    return glm::length(outside);
}

Frustum frustumOf(const Camera& camera, glm::dvec3 position) {
    const double aspect = static_cast<double>(camera.viewportWidth) / camera.viewportHeight;
    return Frustum(position, camera.forward, camera.up, camera.fovY, aspect, camera.nearPlane,
                   camera.farPlane);
}

} // namespace

Scheduler::Scheduler(BatchCatalog& catalog, cache::TerminalSetCache& cache, SchedulerOptions options)
    : catalog_(catalog), cache_(cache), options_(std::move(options)),
      lod_(catalog.index().cells().size(), CellLod::Extruded) {
    const scene::LodProfile& lod = options_.lod;
    if (!(lod.maxScreenSpaceError > 0.0) || !std::isfinite(lod.maxScreenSpaceError))
        throw std::invalid_argument("lod.maxScreenSpaceError must be finite and > 0");
    if (!(lod.geometricError[1] > 0.0) || !std::isfinite(lod.geometricError[1]))
        throw std::invalid_argument("lod.geometricError[1] must be finite and > 0");
    if (!(lod.hysteresis >= 0.0 && lod.hysteresis < 1.0))
        throw std::invalid_argument("lod.hysteresis must lie in [0, 1)");
    if (!(options_.maxMillisecondsPerFrame >= 0.0))
        throw std::invalid_argument("maxMillisecondsPerFrame must be >= 0");
    if (!(options_.prefetchSeconds >= 0.0) || !std::isfinite(options_.prefetchSeconds))
        throw std::invalid_argument("prefetchSeconds must be finite and >= 0");
    if (!(options_.treeGeometricError >= 0.0) || !std::isfinite(options_.treeGeometricError))
        throw std::invalid_argument("treeGeometricError must be finite and >= 0");
    for (uint32_t i = 0; i < backgroundThreads(); ++i) threads_.emplace_back([this] { workerLoop(); });
}

bool Scheduler::prefetchThread() const {
    return options_.workers == 0 && options_.prefetchInBackground;
}

uint32_t Scheduler::backgroundThreads() const {
    return options_.workers > 0 ? options_.workers : (prefetchThread() ? 1 : 0);
}

bool Scheduler::inUpdate(const Request& request) const {
    return options_.workers == 0 && !(request.prefetch && prefetchThread());
}

Scheduler::~Scheduler() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : threads_) t.join();
}

CellLod Scheduler::nextLod(CellLod previous, double sse) const {
    const double maxSse = options_.lod.maxScreenSpaceError;
    const double band = options_.lod.hysteresis;
    if (sse > maxSse * (1.0 + band)) return CellLod::Terminals;
    if (sse < maxSse * (1.0 - band)) return CellLod::Extruded;
    return previous;
}

double Scheduler::screenSpaceError(double distance, const Camera& camera) const {
    if (distance <= 0.0) return std::numeric_limits<double>::infinity();
    return options_.lod.geometricError[1] * camera.viewportHeight /
           (distance * 2.0 * std::tan(camera.fovY * 0.5));
}

bool Scheduler::isTreeBatch(uint32_t batch) const {
    return catalog_.batch(batch).grammar >= catalog_.scene().buildingGrammars.size();
}

bool Scheduler::wantsTrees(double distance, const Camera& camera) const {
    if (options_.treeGeometricError <= 0.0) return true;
    if (distance <= 0.0) return true;
    const double sse =
        options_.treeGeometricError * camera.viewportHeight / (distance * 2.0 * std::tan(camera.fovY * 0.5));
    return sse > options_.lod.maxScreenSpaceError;
}

bool Scheduler::requestIfMissing(uint32_t batch, double sse, bool prefetch, std::vector<Request>& queue,
                                 FrameDecision& frame) {
    // With workers a set evicted to disk is read back by a worker, like one generated, so the
    // frame never waits for the disk; without, the frame reads it itself, through
    // getOrGenerate where a prefetch thread may be reading the same set: it joins that read
    // instead of making a second.
    const cache::BatchKey& key = catalog_.key(batch);
    const bool readsDisk = options_.workers == 0 && !prefetchThread();
    std::shared_ptr<const grammar::TerminalSet> set = readsDisk ? cache_.find(key) : cache_.findInMemory(key);
    if (!set) {
        queue.push_back({batch, sse, prefetch});
        return false;
    }
    if (!prefetch && prefetchThread()) frame.readySets.push_back(std::move(set));
    return true;
}

FrameDecision Scheduler::update(const Camera& camera, double timeSeconds) {
    const auto begin = std::chrono::steady_clock::now();
    if (camera.viewportWidth == 0 || camera.viewportHeight == 0)
        throw std::invalid_argument("camera viewport must be at least 1 x 1 pixels");
    const Frustum frustum = frustumOf(camera, camera.position);
    const auto cells = catalog_.index().cells();
    const auto boxOf = [&](size_t i) {
        return std::pair{glm::dvec3(cells[i].lo, cells[i].zMin), glm::dvec3(cells[i].hi, cells[i].zMax)};
    };

    FrameDecision frame;
    std::vector<Request> queue;
    std::vector<int32_t> decisionOf(cells.size(), -1); // visible Terminals cells: index in frame.cells
    const auto busy = [&](uint32_t batch) {
        std::lock_guard lock(mutex_);
        const uint64_t digest = catalog_.key(batch).digest();
        return failed_.contains(digest) ? Busy::Failed
                                        : (inFlight_.contains(digest) ? Busy::Generating : Busy::No);
    };

    for (size_t i = 0; i < cells.size(); ++i) {
        const auto [lo, hi] = boxOf(i);
        const double distance = distanceToBox(camera.position, lo, hi);
        const double sse = screenSpaceError(distance, camera);
        lod_[i] = options_.forcedLod ? *options_.forcedLod : nextLod(lod_[i], sse);
        if (!frustum.intersectsBox(lo, hi)) continue;
        CellDecision decision{cells[i].cell, distance, sse, lod_[i], {}, {}};
        decision.treesAsTerminals = wantsTrees(distance, camera);
        if (lod_[i] == CellLod::Terminals) {
            ++frame.terminalCells;
            const uint32_t first = catalog_.firstBatchOf(cells[i].cell);
            const uint32_t count = static_cast<uint32_t>(catalog_.index().batchesOf(cells[i].cell).size());
            for (uint32_t b = first; b < first + count; ++b) {
                if (isTreeBatch(b) && !decision.treesAsTerminals) continue;
                const Busy state = busy(b);
                if (state == Busy::Failed) continue;
                // Without workers a visible batch is never left pending: one the background
                // thread is prefetching is queued all the same, and its getOrGenerate joins it.
                if (state == Busy::Generating && options_.workers > 0) {
                    decision.requested.push_back(b);
                } else if (requestIfMissing(b, sse, false, queue, frame)) {
                    decision.ready.push_back(b);
                } else {
                    decision.requested.push_back(b);
                }
            }
            frame.readyBatches += static_cast<uint32_t>(decision.ready.size());
            frame.requestedBatches += static_cast<uint32_t>(decision.requested.size());
            decisionOf[i] = static_cast<int32_t>(frame.cells.size());
        }
        frame.cells.push_back(std::move(decision));
    }

    if (lastPosition_ && timeSeconds > lastTime_ && options_.prefetchSeconds > 0.0) {
        const glm::dvec3 velocity = (camera.position - *lastPosition_) / (timeSeconds - lastTime_);
        const glm::dvec3 predicted = camera.position + velocity * options_.prefetchSeconds;
        if (predicted != camera.position) {
            const Frustum ahead = frustumOf(camera, predicted);
            const size_t before = queue.size();
            for (size_t i = 0; i < cells.size(); ++i) {
                // A visible Terminals cell's batches are requested as visible already, but for
                // its trees while they are billboards: those it will want as the camera nears.
                const bool visible = decisionOf[i] >= 0;
                if (visible && frame.cells[size_t(decisionOf[i])].treesAsTerminals) continue;
                const auto [lo, hi] = boxOf(i);
                const double distance = distanceToBox(predicted, lo, hi);
                const double sse = screenSpaceError(distance, camera);
                const CellLod lod = options_.forcedLod ? *options_.forcedLod : nextLod(lod_[i], sse);
                if (lod != CellLod::Terminals || !ahead.intersectsBox(lo, hi)) continue;
                const uint32_t first = catalog_.firstBatchOf(cells[i].cell);
                const uint32_t count =
                    static_cast<uint32_t>(catalog_.index().batchesOf(cells[i].cell).size());
                for (uint32_t b = first; b < first + count; ++b) {
                    if (isTreeBatch(b) ? !wantsTrees(distance, camera) : visible) continue;
                    if (busy(b) == Busy::No) requestIfMissing(b, sse, true, queue, frame);
                }
            }
            frame.prefetchRequests = static_cast<uint32_t>(queue.size() - before);
        }
    }
    lastPosition_ = camera.position;
    lastTime_ = timeSeconds;

    // Visible before prefetch, then by sse; the batch index makes ties deterministic.
    std::sort(queue.begin(), queue.end(), [](const Request& a, const Request& b) {
        return std::tuple(a.prefetch, -a.sse, a.batch) < std::tuple(b.prefetch, -b.sse, b.batch);
    });

    const size_t cap = options_.maxBatchesPerFrame == 0 ? queue.size() : options_.maxBatchesPerFrame;
    const auto budgetSpent = [&] {
        if (options_.maxMillisecondsPerFrame <= 0.0 || frame.started.empty()) return false;
        const std::chrono::duration<double, std::milli> elapsed = std::chrono::steady_clock::now() - begin;
        return elapsed.count() >= options_.maxMillisecondsPerFrame;
    };
    for (const Request& request : queue) {
        if (frame.started.size() >= cap || budgetSpent()) break;
        const cache::BatchKey& key = catalog_.key(request.batch);
        if (inUpdate(request)) {
            bool ok = true;
            try {
                auto set = cache_.getOrGenerate(key, [&] { return catalog_.generate(request.batch); });
                if (!request.prefetch && prefetchThread()) frame.readySets.push_back(std::move(set));
            } catch (const std::exception&) {
                ok = false;
            }
            std::lock_guard lock(mutex_);
            ++generated_;
            if (!ok) ++failedCount_, failed_.insert(key.digest());
            if (ok && !request.prefetch) {
                // Its cell is visible Terminals (only those queue visible requests): move it to ready.
                const auto cellPos = static_cast<size_t>(
                    catalog_.index().boundsOf(catalog_.batch(request.batch).cell) - cells.data());
                CellDecision& decision = frame.cells[decisionOf[cellPos]];
                std::erase(decision.requested, request.batch);
                decision.ready.push_back(request.batch);
                std::sort(decision.ready.begin(), decision.ready.end());
                ++frame.readyBatches, --frame.requestedBatches;
            }
        } else {
            {
                // Only this thread adds jobs, so the count can only drop before the insert below.
                std::lock_guard lock(mutex_);
                if (inFlight_.size() >= 2 * size_t{backgroundThreads()}) break;
            }
            Job job{request.batch, key, catalog_.inputsOf(request.batch)};
            std::lock_guard lock(mutex_);
            inFlight_.insert(key.digest());
            jobs_.push_back(std::move(job));
            wake_.notify_one();
        }
        frame.started.push_back(request.batch);
        if (request.prefetch) ++frame.prefetchStarted;
    }
    std::lock_guard lock(mutex_);
    frame.inFlight = static_cast<uint32_t>(inFlight_.size());
    return frame;
}

void Scheduler::run(Job job) {
    bool ok = true;
    std::shared_ptr<const grammar::TerminalSet> set;
    try {
        set =
            cache_.getOrGenerate(job.key, [&] { return catalog_.generate(job.batch, job.inputs, job.key); });
    } catch (const std::exception&) {
        ok = false;
    }
    if (set && options_.onBackgroundSet) options_.onBackgroundSet(job.key.digest(), set);
    std::lock_guard lock(mutex_);
    const uint64_t digest = job.key.digest();
    inFlight_.erase(digest);
    ++generated_;
    if (!ok) ++failedCount_, failed_.insert(digest);
    idle_.notify_all();
}

void Scheduler::workerLoop() {
    std::optional<tbb::task_arena> alone;
    if (prefetchThread()) {
        // The prefetch thread runs on what the frame leaves idle: at normal priority it took
        // cores from the rasteriser's threads and slowed the median frame (about 5 % on two
        // cores). A frame that needs a batch this thread holds waits for it, and so leaves it
        // the core it needs.
        sched_param param{};
        pthread_setschedparam(pthread_self(), SCHED_IDLE, &param);
        // Generation is parallel (TBB): in an arena of this thread alone, all of it stays at
        // idle priority rather than on TBB's workers.
        alone.emplace(1);
    }
    for (;;) {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [&] { return stopping_ || !jobs_.empty(); });
        if (stopping_) return;
        Job job = std::move(jobs_.front());
        jobs_.pop_front();
        lock.unlock();
        if (alone)
            alone->execute([&] { run(std::move(job)); });
        else
            run(std::move(job));
    }
}

void Scheduler::drain() {
    std::unique_lock lock(mutex_);
    idle_.wait(lock, [&] { return inFlight_.empty(); });
}

uint64_t Scheduler::generatedBatches() const {
    std::lock_guard lock(mutex_);
    return generated_;
}

uint64_t Scheduler::failedBatches() const {
    std::lock_guard lock(mutex_);
    return failedCount_;
}

} // namespace hexlod::cells
