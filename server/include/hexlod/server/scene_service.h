// The scene as the HTTP service sees it: the batch catalog and its caches, the published
// state of every batch (key and version), content generation on demand, and edits with
// their journal and change events. The HTTP layer (server.h) is a thin shell over it.
//
// Concurrency. BatchCatalog::setParams must not run while a generation reads the catalog,
// so a shared_mutex guards the catalog: edits hold it exclusively while they apply, journal
// (fdatasync) and publish; a generation holds it shared only to snapshot the batch's inputs
// and key (as cells::Scheduler does), then expands unlocked. Readers of keys and versions
// (the cell index, content URL checks) never touch that lock: they read the published
// state, which an edit updates under a short lock of its own once its journal line is
// durable. So a client can only see a new key after its edit was acknowledged to disk, and
// a cached content request never waits for an fsync.
//
// Edits and undos must come from one thread at a time (the server runs them on one thread),
// which keeps journal order and catalog order the same.
#pragma once

#include "hexlod/cache/terminal_set_cache.h"
#include "hexlod/cells/batch_catalog.h"
#include "hexlod/server/edit_journal.h"
#include "hexlod/server/edit_request.h"
#include "hexlod/server/event_hub.h"
#include "hexlod/server/generation_pool.h"
#include "hexlod/server/metrics.h"
#include "hexlod/server/payload_cache.h"
#include "hexlod/server/shape_assets.h"
#include "hexlod/server/species_bakery.h"
#include "hexlod/server/splice_bases.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <shared_mutex>
#include <span>
#include <string>
#include <unordered_set>
#include <vector>

namespace hexlod::server {

struct ServiceOptions {
    std::string journalPath;      // required
    bool journalRepair = false;   // see EditJournal
    bool journalReadOnly = false; // replay only: nothing truncated, edits refused (hexlod export)
    uint32_t generationWorkers = 2;
    uint32_t generationQueue = 64; // distinct batches waiting to generate; beyond it: 503
    uint64_t terminalPayloadBytes = uint64_t(192) << 20;
    uint64_t extrudedPayloadBytes = uint64_t(64) << 20;
    // Released expansion blocks kept for reuse (grammar::setBulkPoolLimit, process-wide): part
    // of the service's memory besides its caches, so it is bounded here.
    uint64_t bulkPoolBytes = uint64_t(256) << 20;
    int zstdLevel = 3;
    bool editsNeedToken = false; // for the summary's capabilities
};

enum class PayloadKind { TerminalSet, ExtrudedSet };

struct BatchState {
    cache::BatchKey key;
    uint64_t version = 1; // bumped by every edit or undo that changes the key
};

// A reply body for an edit or undo: status 200 with the change, or an error.
struct EditOutcome {
    int status = 200;
    nlohmann::json body;
};

class SceneService {
public:
    // Indexes the scene, opens the journal and replays it. `log` gets one line per thing
    // started, skipped, repaired or left out. Returns nullptr with `error` when the scene
    // cannot be indexed or the journal cannot be opened.
    static std::unique_ptr<SceneService> create(scene::BuiltScene scene, cache::CacheOptions cacheOptions,
                                                ServiceOptions options, std::vector<std::string>& log,
                                                std::string& error);
    ~SceneService();
    SceneService(const SceneService&) = delete;
    SceneService& operator=(const SceneService&) = delete;

    // Read side, any thread.
    nlohmann::json summary() const;
    // The cell index JSON of the current state, built once per state.
    struct IndexView {
        std::shared_ptr<const std::string> json;
        std::string etag; // weak: W/"<last seq>-<state digest>"
    };
    IndexView cellIndex();
    std::string stateEtag() const;
    std::optional<uint32_t> findBatch(cells::HexCoord cell, uint32_t grammar) const;
    BatchState batchState(uint32_t batch) const;
    std::string contentUrl(PayloadKind kind, uint32_t batch, const cache::BatchKey& key) const;
    std::optional<nlohmann::json> building(uint32_t id) const;
    nlohmann::json history(uint64_t since, size_t limit) const;
    nlohmann::json hello() const; // the first event of every event stream

    // The payload of `batch` under `key`: `done` runs inline on a cached hit, else on a
    // generation thread; 404 when `key` is not (or no longer) the batch's key, 503 when the
    // generation queue is full.
    void fetch(PayloadKind kind, uint32_t batch, const cache::BatchKey& key,
               std::function<void(const PayloadOutcome&)> done);

    // Terminal meshes and impostors (shape_assets.h). Attach before the service answers its
    // first request: the summary is rebuilt, and the assets are read without a lock after.
    void attachShapeAssets(ShapeAssets assets);
    const ShapeAssets& shapeAssets() const { return assets_; }
    // "/api/v1/meshes/{grammar}/{shape}/{hash}.glb"; empty when the shape has no mesh served.
    std::string meshUrl(uint32_t grammar, uint32_t shape) const;
    // "/api/v1/meshes/{grammar}/{shape}/{hash}.coarse.glb", its coarse mesh; empty without one.
    std::string coarseMeshUrl(uint32_t grammar, uint32_t shape) const;
    // "/api/v1/impostors/{grammar}/{shape}/{key}" + suffix (".albedo.png", ".normal.png",
    // ".exr"); empty when the shape has no impostor.
    std::string impostorUrl(uint32_t grammar, uint32_t shape, const char* suffix) const;
    // "/api/v1/tree-impostors/{species}/{key}" + suffix; empty when no such species is served.
    std::string speciesImpostorUrl(uint32_t species, const char* suffix) const;
    // The served species: those of the attached assets, then those baked for edits since.
    std::optional<SpeciesAsset> species(uint32_t index) const;
    size_t speciesCount() const;
    // Bakes a species for trees that an edit or undo leaves with values no served species has
    // (species_bakery.h), at most kMaxEditedSpecies of them held at once, baking or served.
    // A bake whose values no tree has any more by its turn is dropped; at the cap, species
    // baked for edits that no tree has the values of any more are retired to make room.
    // Attach after the shape assets, and only when they serve species.
    void attachSpeciesBakery(std::unique_ptr<SpeciesBakery> bakery);
    static constexpr size_t kMaxEditedSpecies = 64;

    // Write side, one thread at a time.
    EditOutcome edit(const EditSpec& edit);
    EditOutcome undo();

    EventHub& events() { return events_; }
    Metrics& metrics() { return metrics_; }
    void renderMetrics(PrometheusText& out) const; // caches, generation, journal, events
    uint64_t expansions() const { return expansions_.load(); }
    uint64_t lastSeq() const;
    const std::vector<std::string>& notes() const { return notes_; }
    void stop(); // before destruction: queued generations get 503

    // Runs `f(const cells::BatchCatalog&)` under the shared catalog lock (tests, export).
    template <typename F> auto withCatalog(F&& f) const {
        std::shared_lock lock(catalogMutex_);
        return f(*catalog_);
    }

private:
    enum class Status { Applied, Undone, Skipped };
    struct HistoryRecord {
        JournalEntry entry;
        Status status = Status::Applied;
        std::string reason;    // Skipped: why
        size_t changed = 0;    // batches whose key changed
        uint64_t undoneBy = 0; // Undone: the seq of the undo
    };

    SceneService(scene::BuiltScene scene, cache::CacheOptions cacheOptions, ServiceOptions options);
    void replay(const std::vector<JournalEntry>& entries, std::vector<std::string>& log);
    void replayEdit(const JournalEntry& entry, std::vector<std::string>& log);
    void replayUndo(const JournalEntry& entry, std::vector<std::string>& log);
    // Publishes key changes: versions, digest, last seq. Returns the change list for replies
    // and events.
    nlohmann::json publish(const std::vector<cells::KeyChange>& changes, uint64_t seq);
    nlohmann::json changeReply(const char* op, uint64_t seq, nlohmann::json changed) const;
    PayloadOutcome produce(PayloadKind kind, uint32_t batch, const cache::BatchKey& key);
    PayloadBytes storeExtruded(uint32_t batch, const cache::BatchKey& key, const grammar::ExtrudedSet& set);
    // `key`'s terminal set spliced into the batch's last one, when that is still decoded in
    // memory: only the buildings whose inputs differ are expanded (splice_bases.h). Stores
    // the extruded set the same way when the last one's payload is cached, into `extruded`.
    // None: expand the whole batch.
    std::optional<grammar::TerminalSet> splice(uint32_t batch, const cache::BatchKey& key,
                                               std::span<const grammar::BuildingInput> inputs,
                                               PayloadBytes& extruded);
    // Beyond this share of a batch's buildings changed, the whole batch is expanded.
    static constexpr double kMaxSplicedShare = 0.5;
    PayloadOutcome staleOutcome(PayloadKind kind, uint32_t batch) const;
    nlohmann::json staticSummary() const;
    nlohmann::json shapeJson(uint32_t grammar, uint32_t shape) const;
    nlohmann::json speciesJson() const;                    // under speciesMutex_
    nlohmann::json speciesEntryJson(uint32_t index) const; // under speciesMutex_
    // Asks the bakery for every value set of the changed tree batches that no species has.
    // Under catalogMutex_ held exclusively.
    void requestMissingSpecies(const std::vector<cells::KeyChange>& changes);
    // Retires the served species baked for edits whose values no tree has; under
    // catalogMutex_ and speciesMutex_.
    void retireUnusedSpecies();
    // Species baked for edits held now, against kMaxEditedSpecies: baking, or served and not
    // retired. Under speciesMutex_.
    size_t editedHeld() const;
    // Whether a tree of `grammar` has these values now; under catalogMutex_.
    bool treesHaveValues(uint32_t grammar, const std::vector<float>& values) const;
    // The bakery's stillWanted for a requested value set: false, and its place freed, when no
    // tree has the values any more.
    bool speciesStillWanted(const std::pair<uint32_t, std::vector<float>>& values);
    void addBakedSpecies(const SpeciesRequest& request, std::optional<SpeciesAsset> asset,
                         const std::string& error);
    void renderSpeciesMetrics(PrometheusText& out) const;
    std::string buildIndex() const; // under stateMutex_ shared

    ServiceOptions options_;
    std::unique_ptr<cells::BatchCatalog> catalog_;
    mutable std::shared_mutex catalogMutex_;
    std::unique_ptr<EditJournal> journal_;
    uint64_t decodedBudget_ = 0;
    cache::TerminalSetCache decoded_;
    PayloadCache terminalPayloads_, extrudedPayloads_;
    SpliceBases spliceBases_;
    GenerationPool pool_;
    EventHub events_;
    Metrics metrics_;
    std::vector<std::string> notes_;
    nlohmann::json staticSummary_;
    ShapeAssets assets_;
    bool assetsAttached_ = false;
    std::vector<cells::BuildingRef> buildingRefs_; // by building id

    // Published state, guarded by stateMutex_.
    mutable std::shared_mutex stateMutex_;
    std::vector<BatchState> state_;
    uint64_t stateDigest_ = 0;
    uint64_t lastSeq_ = 0;
    std::shared_ptr<const std::string> indexJson_;
    uint64_t indexBuiltFor_ = ~uint64_t(0); // lastSeq_ the cached index was built for
    std::mutex indexMutex_;

    // Edit side, guarded by catalogMutex_ held exclusively.
    std::vector<HistoryRecord> history_;
    std::vector<size_t> undoStack_; // indices into history_ of edits not undone

    mutable std::mutex failedMutex_;
    std::unordered_set<uint64_t> failedKeys_; // digests whose expansion failed: not retried
    std::atomic<uint64_t> expansions_{0};

    // Tree species: the attached ones, then those baked for edits; an index is its layer.
    mutable std::mutex speciesMutex_;
    std::vector<SpeciesAsset> species_;
    // (grammar, values) of every species served or being baked, and of bakes that failed (not
    // retried): the value is its state.
    enum class SpeciesState { Served, Baking, Failed };
    std::map<std::pair<uint32_t, std::vector<float>>, SpeciesState> speciesStates_;
    size_t startSpecies_ = 0;     // the attached ones: never retired
    uint64_t speciesDropped_ = 0; // bakes dropped at their turn since start, for /metrics
    // Last, so that it is destroyed first: its thread calls addBakedSpecies.
    std::unique_ptr<SpeciesBakery> bakery_;
};

} // namespace hexlod::server
