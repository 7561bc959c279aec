// SceneService: construction, journal replay, edits and undos, and the published state.
// Content generation is in scene_service_content.cpp, the JSON views in scene_service_json.cpp.
#include "hexlod/server/scene_service.h"

#include "hexlod/grammar/bulk_allocator.h"
#include "hexlod/grammar/position_hash.h"
#include "hexlod/server/http_types.h"

#include <chrono>

namespace hexlod::server {
namespace {

using Json = nlohmann::json;

uint64_t stateTerm(uint32_t batch, const cache::BatchKey& key) {
    return grammar::mixBits(key.digest() ^ grammar::mixBits(batch));
}

Json editError(int status, const EditError& error) {
    Json body = {{"status", status}, {"error", error.text()}};
    if (!error.field.empty()) body["field"] = error.field;
    return body;
}

std::string mebibytes(uint64_t bytes) {
    return std::to_string(bytes >> 20) + " MiB";
}

} // namespace

SceneService::SceneService(scene::BuiltScene scene, cache::CacheOptions cacheOptions, ServiceOptions options)
    : options_(std::move(options)), catalog_(std::make_unique<cells::BatchCatalog>(std::move(scene))),
      decodedBudget_(cacheOptions.memoryBudgetBytes), decoded_(std::move(cacheOptions)),
      terminalPayloads_(options_.terminalPayloadBytes), extrudedPayloads_(options_.extrudedPayloadBytes),
      pool_(options_.generationWorkers, options_.generationQueue) {
    const cells::BatchCatalog& catalog = *catalog_;
    state_.resize(catalog.batchCount());
    for (uint32_t b = 0; b < state_.size(); ++b) {
        state_[b].key = catalog.key(b);
        stateDigest_ ^= stateTerm(b, state_[b].key);
    }
    buildingRefs_.resize(catalog.scene().buildingOrigins.size());
    for (uint32_t g = 0; g < catalog.index().buildingGrammarCount(); ++g) {
        const auto& list = catalog.grammar(g).buildings;
        for (uint32_t i = 0; i < list.size(); ++i)
            if (list[i].id < buildingRefs_.size()) buildingRefs_[list[i].id] = {g, i};
    }
}

SceneService::~SceneService() {
    stop();
}

std::unique_ptr<SceneService> SceneService::create(scene::BuiltScene scene, cache::CacheOptions cacheOptions,
                                                   ServiceOptions options, std::vector<std::string>& log,
                                                   std::string& error) {
    if (options.journalPath.empty()) {
        error = "no edit journal path";
        return nullptr;
    }
    const std::string sceneName = scene.config.name;
    std::unique_ptr<SceneService> service;
    try {
        service.reset(new SceneService(std::move(scene), std::move(cacheOptions), std::move(options)));
    } catch (const std::exception& e) {
        error = std::string("cannot index the scene: ") + e.what();
        return nullptr;
    }
    SceneService& s = *service;
    grammar::setBulkPoolLimit(s.options_.bulkPoolBytes);
    for (const std::string& note : s.catalog_->scene().notes) s.notes_.push_back(note);
    JournalOpenOptions journalOptions;
    journalOptions.repair = s.options_.journalRepair;
    journalOptions.readOnly = s.options_.journalReadOnly;
    journalOptions.scene = sceneName;
    std::vector<JournalEntry> entries;
    std::vector<std::string> journalNotes;
    s.journal_ = EditJournal::open(s.options_.journalPath, journalOptions, entries, journalNotes, error);
    if (!s.journal_) return nullptr;
    for (const std::string& note : journalNotes) s.notes_.push_back(note);
    s.replay(entries, s.notes_);
    s.staticSummary_ = s.staticSummary();

    const cells::CellIndex& index = s.catalog_->index();
    s.notes_.push_back("cells: " + std::to_string(index.cells().size()) + " cells, " +
                       std::to_string(s.catalog_->batchCount()) + " batches of " +
                       std::to_string(index.buildingCount()) + " buildings and " +
                       std::to_string(index.treeCount()) + " trees, generated on demand");
    s.notes_.push_back("generation: at most " + std::to_string(std::max(1u, s.options_.generationWorkers)) +
                       " batches at once, " + std::to_string(s.options_.generationQueue) +
                       " more may wait; beyond that 503 with Retry-After");
    s.notes_.push_back("cache: decoded terminal sets " + mebibytes(s.decodedBudget_) + ", " +
                       "encoded payloads " + mebibytes(s.options_.terminalPayloadBytes) +
                       " (terminal sets) + " + mebibytes(s.options_.extrudedPayloadBytes) +
                       " (extruded sets)");
    for (const std::string& line : s.notes_) log.push_back(line);
    return service;
}

void SceneService::stop() {
    bakery_.reset(); // its thread calls back into the service: it goes first
    pool_.stop();
    events_.closeAll();
}

uint64_t SceneService::lastSeq() const {
    std::shared_lock lock(stateMutex_);
    return lastSeq_;
}

std::string SceneService::stateEtag() const {
    std::shared_lock lock(stateMutex_);
    return "W/\"" + std::to_string(lastSeq_) + "-" + cache::hexDigest(stateDigest_) + "\"";
}

// --- replay -------------------------------------------------------------------------------

void SceneService::replay(const std::vector<JournalEntry>& entries, std::vector<std::string>& log) {
    size_t edits = 0, undos = 0;
    for (const JournalEntry& entry : entries) {
        if (entry.op == JournalEntry::Op::Edit) {
            replayEdit(entry, log);
            ++edits;
        } else {
            replayUndo(entry, log);
            ++undos;
        }
    }
    size_t skipped = 0;
    for (const HistoryRecord& record : history_) skipped += record.status == Status::Skipped;
    const uint64_t last = entries.empty() ? 0 : entries.back().seq;
    {
        std::unique_lock lock(stateMutex_);
        lastSeq_ = last;
    }
    events_.setBaseline(last);
    log.push_back("journal " + journal_->path() + ": replayed " + std::to_string(edits) + " edits and " +
                  std::to_string(undos) + " undos (" + std::to_string(skipped) + " skipped); next seq " +
                  std::to_string(journal_->nextSeq()));
}

void SceneService::replayEdit(const JournalEntry& entry, std::vector<std::string>& log) {
    HistoryRecord record{entry, Status::Applied, {}, 0, 0};
    EditSpec spec;
    EditError error;
    bool ok =
        editFromJson(entry.selector, entry.params, spec, error) && checkSelector(*catalog_, spec, error);
    if (ok) {
        const cells::EditResult result = catalog_->setParams(spec.selector, spec.params);
        ok = result.ok;
        if (ok) {
            publish(result.changed, entry.seq);
            record.changed = result.changed.size();
        } else {
            error = {fieldOfCatalogError(result.error), result.error};
        }
    }
    if (!ok) {
        record.status = Status::Skipped;
        record.reason = error.text();
        log.push_back("journal: edit " + std::to_string(entry.seq) + " no longer applies (" + record.reason +
                      "): skipped");
    }
    history_.push_back(std::move(record));
    undoStack_.push_back(history_.size() - 1);
}

void SceneService::replayUndo(const JournalEntry& entry, std::vector<std::string>& log) {
    HistoryRecord record{entry, Status::Applied, {}, 0, 0};
    if (undoStack_.empty()) {
        record.status = Status::Skipped;
        record.reason = "no edit to undo";
        log.push_back("journal: undo " + std::to_string(entry.seq) + " finds no edit to undo: skipped");
    } else {
        HistoryRecord& target = history_[undoStack_.back()];
        undoStack_.pop_back();
        if (target.entry.seq != entry.undoes)
            log.push_back("journal: undo " + std::to_string(entry.seq) + " was written for edit " +
                          std::to_string(entry.undoes) + " but reverts edit " +
                          std::to_string(target.entry.seq));
        if (target.status == Status::Applied) {
            const cells::EditResult result = catalog_->undo();
            publish(result.changed, entry.seq);
            record.changed = result.changed.size();
        }
        target.status = target.status == Status::Skipped ? Status::Skipped : Status::Undone;
        target.undoneBy = entry.seq;
    }
    history_.push_back(std::move(record));
}

// --- edits --------------------------------------------------------------------------------

Json SceneService::publish(const std::vector<cells::KeyChange>& changes, uint64_t seq) {
    Json list = Json::array();
    std::unique_lock lock(stateMutex_);
    for (const cells::KeyChange& change : changes) {
        BatchState& state = state_[change.batch];
        stateDigest_ ^= stateTerm(change.batch, state.key) ^ stateTerm(change.batch, change.after);
        state.key = change.after;
        ++state.version;
        const cells::Batch& batch = catalog_->batch(change.batch);
        list.push_back(
            {{"cell", {batch.cell.q, batch.cell.r}},
             {"grammar", batch.grammar},
             {"version", state.version},
             {"key", change.after.hex()},
             {"previous_key", change.before.hex()},
             {"terminal_set", contentUrl(PayloadKind::TerminalSet, change.batch, change.after)},
             {"extruded_set", contentUrl(PayloadKind::ExtrudedSet, change.batch, change.after)},
             {"previous_terminal_set", contentUrl(PayloadKind::TerminalSet, change.batch, change.before)},
             {"previous_extruded_set", contentUrl(PayloadKind::ExtrudedSet, change.batch, change.before)}});
    }
    lastSeq_ = seq;
    lock.unlock();
    // The old versions go before any current content when a tier is full, so that a tuning
    // session does not push the rest of the city out; an undo makes its version current again.
    for (const cells::KeyChange& change : changes) {
        decoded_.markSuperseded(change.before);
        decoded_.markCurrent(change.after);
        for (PayloadCache* tier : {&terminalPayloads_, &extrudedPayloads_}) {
            tier->markSuperseded(change.before);
            tier->markCurrent(change.after);
        }
    }
    return list;
}

Json SceneService::changeReply(const char* op, uint64_t seq, Json changed) const {
    Json cellsChanged = Json::array();
    for (const Json& change : changed)
        if (cellsChanged.empty() || cellsChanged.back() != change["cell"])
            cellsChanged.push_back(change["cell"]);
    return {{"seq", seq},
            {"op", op},
            {"changed", std::move(changed)},
            {"cells", cellsChanged},
            {"index_etag", stateEtag()}};
}

EditOutcome SceneService::edit(const EditSpec& spec) {
    std::unique_lock lock(catalogMutex_);
    EditError error;
    if (!checkSelector(*catalog_, spec, error)) {
        metrics_.recordEdit("edit", "invalid");
        return {400, editError(400, error)};
    }
    const cells::EditResult result = catalog_->setParams(spec.selector, spec.params);
    if (!result.ok) {
        metrics_.recordEdit("edit", "invalid");
        return {400, editError(400, {fieldOfCatalogError(result.error), result.error})};
    }
    JournalEntry entry;
    entry.seq = journal_->nextSeq();
    entry.op = JournalEntry::Op::Edit;
    entry.selector = spec.selectorJson;
    entry.params = spec.paramsJson;
    entry.comment = spec.comment;
    entry.time = utcNow();
    std::string journalError;
    const auto start = std::chrono::steady_clock::now();
    if (!journal_->append(entry, journalError)) {
        catalog_->undo(); // the edit was never acknowledged: take it back
        metrics_.recordEdit("edit", "journal_failed");
        return {503, editError(503, {"", "the edit was not applied: " + journalError})};
    }
    metrics_.recordJournalSync(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    Json changed = publish(result.changed, entry.seq);
    history_.push_back({entry, Status::Applied, {}, result.changed.size(), 0});
    undoStack_.push_back(history_.size() - 1);
    Json reply = changeReply("edit", entry.seq, std::move(changed));
    events_.publish(entry.seq, "edit", jsonText(reply));
    requestMissingSpecies(result.changed);
    metrics_.recordEdit("edit", "ok");
    return {200, std::move(reply)};
}

EditOutcome SceneService::undo() {
    std::unique_lock lock(catalogMutex_);
    if (undoStack_.empty()) {
        metrics_.recordEdit("undo", "invalid");
        return {409, editError(409, {"", "no edit to undo"})};
    }
    HistoryRecord& target = history_[undoStack_.back()];
    JournalEntry entry;
    entry.seq = journal_->nextSeq();
    entry.op = JournalEntry::Op::Undo;
    entry.undoes = target.entry.seq;
    entry.time = utcNow();
    // An undo cannot fail to apply, so it is journaled first: nothing to take back after.
    std::string journalError;
    const auto start = std::chrono::steady_clock::now();
    if (!journal_->append(entry, journalError)) {
        metrics_.recordEdit("undo", "journal_failed");
        return {503, editError(503, {"", "the undo was not applied: " + journalError})};
    }
    metrics_.recordJournalSync(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    undoStack_.pop_back();
    cells::EditResult result;
    if (target.status == Status::Applied) result = catalog_->undo();
    target.status = target.status == Status::Skipped ? Status::Skipped : Status::Undone;
    target.undoneBy = entry.seq;
    Json changed = publish(result.changed, entry.seq);
    history_.push_back({entry, Status::Applied, {}, result.changed.size(), 0});
    Json reply = changeReply("undo", entry.seq, std::move(changed));
    reply["undoes"] = entry.undoes;
    events_.publish(entry.seq, "undo", jsonText(reply));
    requestMissingSpecies(result.changed);
    metrics_.recordEdit("undo", "ok");
    return {200, std::move(reply)};
}

// --- metrics ------------------------------------------------------------------------------

void SceneService::renderMetrics(PrometheusText& out) const {
    metrics_.render(out);
    const cache::CacheStats decoded = decoded_.stats();
    const PayloadCacheStats terminal = terminalPayloads_.stats(), extruded = extrudedPayloads_.stats();
    struct Tier {
        const char* name;
        uint64_t hits, misses, evictions, bytes, entries;
    };
    const Tier tiers[] = {
        {"decoded", decoded.memoryHits + decoded.sharedGenerations, decoded.misses, decoded.evictions,
         decoded.memoryBytes, decoded.memoryEntries},
        {"disk", decoded.diskHits, 0, decoded.diskEvictions, decoded.diskBytes, decoded.diskFiles},
        {"terminal_payload", terminal.hits, terminal.misses, terminal.evictions, terminal.bytes,
         terminal.entries},
        {"extruded_payload", extruded.hits, extruded.misses, extruded.evictions, extruded.bytes,
         extruded.entries},
    };
    const auto perTier = [&](const char* name, const char* type, const char* help, auto field) {
        out.family(name, type, help);
        for (const Tier& t : tiers) out.sample(name, {{"tier", t.name}}, static_cast<double>(field(t)));
    };
    perTier("hexlod_cache_hits_total", "counter", "Cache hits per tier.",
            [](const Tier& t) { return t.hits; });
    perTier("hexlod_cache_misses_total", "counter",
            "Cache misses per tier (the disk tier counts its misses in "
            "the decoded tier's).",
            [](const Tier& t) { return t.misses; });
    perTier("hexlod_cache_evictions_total", "counter", "Entries dropped for the byte budget, per tier.",
            [](const Tier& t) { return t.evictions; });
    perTier("hexlod_cache_bytes", "gauge", "Bytes held per tier.", [](const Tier& t) { return t.bytes; });
    perTier("hexlod_cache_entries", "gauge", "Entries held per tier.",
            [](const Tier& t) { return t.entries; });
    out.family("hexlod_cache_budget_bytes", "gauge", "Byte budget per memory tier.");
    out.sample("hexlod_cache_budget_bytes", {{"tier", "decoded"}}, static_cast<double>(decodedBudget_));
    out.sample("hexlod_cache_budget_bytes", {{"tier", "terminal_payload"}},
               static_cast<double>(terminal.budget));
    out.sample("hexlod_cache_budget_bytes", {{"tier", "extruded_payload"}},
               static_cast<double>(extruded.budget));

    out.family("hexlod_bulk_pool_bytes", "gauge", "Released expansion blocks kept for reuse (bounded).");
    out.sample("hexlod_bulk_pool_bytes", {}, static_cast<double>(grammar::bulkPoolBytes()));
    out.family("hexlod_bulk_pool_limit_bytes", "gauge", "What the expansion block pool may keep.");
    out.sample("hexlod_bulk_pool_limit_bytes", {}, static_cast<double>(options_.bulkPoolBytes));

    const GenerationPoolStats pool = pool_.stats();
    out.family("hexlod_batch_expansions_total", "counter", "Batch expansions (grammar runs) of the service.");
    out.sample("hexlod_batch_expansions_total", {}, static_cast<double>(expansions_.load()));
    out.family("hexlod_generation_running", "gauge", "Content jobs running now.");
    out.sample("hexlod_generation_running", {}, pool.running);
    out.family("hexlod_generation_queued", "gauge", "Content jobs waiting for a worker.");
    out.sample("hexlod_generation_queued", {}, pool.queued);
    out.family("hexlod_generation_joined_total", "counter",
               "Content requests that joined a job already under way.");
    out.sample("hexlod_generation_joined_total", {}, static_cast<double>(pool.joined));
    out.family("hexlod_generation_rejected_total", "counter", "Content requests answered 503: queue full.");
    out.sample("hexlod_generation_rejected_total", {}, static_cast<double>(pool.rejected));

    const EventHubStats hub = events_.stats();
    out.family("hexlod_sse_clients", "gauge", "Event-stream subscribers connected now.");
    out.sample("hexlod_sse_clients", {}, hub.subscribers);
    out.family("hexlod_sse_events_total", "counter", "Change events published.");
    out.sample("hexlod_sse_events_total", {}, static_cast<double>(hub.published));
    out.family("hexlod_sse_dropped_total", "counter",
               "Subscribers dropped: their queue overflowed or a write stalled past the write timeout.");
    out.sample("hexlod_sse_dropped_total", {}, static_cast<double>(hub.dropped));
    out.family("hexlod_journal_seq", "gauge", "Sequence number of the last journal entry.");
    out.sample("hexlod_journal_seq", {}, static_cast<double>(lastSeq()));
    renderSpeciesMetrics(out);
}

} // namespace hexlod::server
