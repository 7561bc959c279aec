// SceneService: content on demand. A request first looks in the encoded-payload tier of its
// kind; a miss becomes a job on the generation pool, deduplicated per (kind, key). The job
// goes through the catalog and TerminalSetCache::getOrGenerate, so terminal sets are
// expanded once per key whoever asks. One expansion yields both sets (grammar::BatchResult),
// and the extruded set is encoded into its tier at once: a cell's extruded and terminal sets
// cost one expansion. The decoded tier keeps terminal sets only, so an extruded request whose
// terminal set is already decoded (or on disk) expands again: the price of not doubling the
// decoded tier's memory for a set that is only ever sent, never read. An edited batch whose
// last set is still decoded is spliced instead: only the buildings the edit changed expand.
#include "hexlod/server/scene_service.h"

#include "hexlod/grammar/batch_splice.h"
#include "hexlod/grammar/extruded_set_codec.h"
#include "hexlod/grammar/terminal_set_codec.h"

#include <chrono>
#include <stdexcept>

namespace hexlod::server {
namespace {

const char* kindPath(PayloadKind kind) {
    return kind == PayloadKind::TerminalSet ? "terminal-sets" : "extruded-sets";
}

uint64_t flightKey(PayloadKind kind, const cache::BatchKey& key) {
    return key.digest() ^ (kind == PayloadKind::TerminalSet ? 0 : 0x5bd1e9955bd1e995ull);
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

std::optional<uint32_t> SceneService::findBatch(cells::HexCoord cell, uint32_t grammar) const {
    const auto batches = catalog_->index().batchesOf(cell); // the index never changes: no lock
    for (const cells::Batch& b : batches)
        if (b.grammar == grammar) return static_cast<uint32_t>(&b - catalog_->index().batches().data());
    return std::nullopt;
}

BatchState SceneService::batchState(uint32_t batch) const {
    std::shared_lock lock(stateMutex_);
    return state_.at(batch);
}

std::string SceneService::contentUrl(PayloadKind kind, uint32_t batch, const cache::BatchKey& key) const {
    const cells::Batch& b = catalog_->batch(batch);
    return std::string("/api/v1/") + kindPath(kind) + "/" + std::to_string(b.cell.q) + "," +
           std::to_string(b.cell.r) + "/" + std::to_string(b.grammar) + "/" + key.hex();
}

PayloadOutcome SceneService::staleOutcome(PayloadKind kind, uint32_t batch) const {
    const BatchState now = batchState(batch);
    const std::string url = contentUrl(kind, batch, now.key);
    return {nullptr, 404,
            "this key is not the batch's current key (an edit changed it); the current content is " + url,
            url};
}

void SceneService::fetch(PayloadKind kind, uint32_t batch, const cache::BatchKey& key,
                         std::function<void(const PayloadOutcome&)> done) {
    if (!(batchState(batch).key == key)) return done(staleOutcome(kind, batch));
    PayloadCache& tier = kind == PayloadKind::TerminalSet ? terminalPayloads_ : extrudedPayloads_;
    if (PayloadBytes hit = tier.find(key)) return done({std::move(hit), 200, {}, {}});
    {
        std::lock_guard lock(failedMutex_);
        if (failedKeys_.contains(key.digest()))
            return done(
                {nullptr, 500, "this batch failed to generate (see the service log); not retried", {}});
    }
    const auto admission = pool_.submit(
        flightKey(kind, key), [this, kind, batch, key] { return produce(kind, batch, key); }, done);
    if (admission == GenerationPool::Admission::Rejected)
        done({nullptr, 503, "too many batches are waiting to generate; retry shortly", {}});
}

PayloadBytes SceneService::storeExtruded(uint32_t batch, const cache::BatchKey& key,
                                         const grammar::ExtrudedSet& set) {
    const cells::Batch& b = catalog_->batch(batch);
    grammar::ExtrudedSetHeader header;
    header.cell = {b.cell.q, b.cell.r};
    header.grammar = b.grammar;
    header.grammarHash = key.grammarHash;
    header.key = key.digest();
    const glm::dvec3 origin = catalog_->cellOrigin(b.cell);
    for (int i = 0; i < 3; ++i) header.cellOrigin[i] = origin[i];
    auto bytes = std::make_shared<const std::vector<uint8_t>>(
        grammar::encodeExtrudedSet(header, set, options_.zstdLevel));
    extrudedPayloads_.insert(key, bytes);
    return bytes;
}

std::optional<grammar::TerminalSet> SceneService::splice(uint32_t batch, const cache::BatchKey& key,
                                                         std::span<const grammar::BuildingInput> inputs,
                                                         PayloadBytes& extruded) {
    const std::optional<SpliceBases::Plan> plan = spliceBases_.plan(batch, key, inputs, kMaxSplicedShare);
    if (!plan) return std::nullopt;
    const cache::TerminalSetCache::SetPtr base = decoded_.findInMemory(plan->base);
    if (!base) return std::nullopt;
    std::vector<grammar::BuildingInput> changed;
    changed.reserve(plan->changed.size());
    for (const uint32_t i : plan->changed) changed.push_back(inputs[i]);
    const grammar::BatchResult part = catalog_->expand(batch, changed, key);
    if (part.failed) return std::nullopt; // the whole batch's expansion reports it
    grammar::TerminalSet set = grammar::spliceTerminals(*base, part.terminals, plan->ids);
    if (set.records.size() > grammar::ExpansionLimits{}.maxTerminalsPerBatch) return std::nullopt;
    set.header.key = key.digest();
    if (const PayloadBytes old = extrudedPayloads_.peek(plan->base)) {
        grammar::ExtrudedSetHeader header;
        grammar::ExtrudedSet oldSet;
        std::string error;
        if (grammar::decodeExtrudedSet(*old, header, oldSet, error))
            extruded = storeExtruded(batch, key, grammar::spliceExtruded(oldSet, part.extruded, plan->ids));
    }
    return set;
}

PayloadOutcome SceneService::produce(PayloadKind kind, uint32_t batch, const cache::BatchKey& key) {
    PayloadCache& tier = kind == PayloadKind::TerminalSet ? terminalPayloads_ : extrudedPayloads_;
    // A job of the other kind may have made it while this one waited.
    if (PayloadBytes ready = tier.peek(key)) return {std::move(ready), 200, {}, {}};
    std::vector<grammar::BuildingInput> inputs;
    {
        std::shared_lock lock(catalogMutex_);
        if (!(catalog_->key(batch) == key)) return staleOutcome(kind, batch);
        inputs = catalog_->inputsOf(batch);
    }
    const auto start = std::chrono::steady_clock::now();
    bool expanded = false, spliced = false;
    PayloadBytes extruded;
    const auto expand = [&](bool maySplice) {
        expanded = true;
        ++expansions_;
        if (std::optional<grammar::TerminalSet> set =
                maySplice ? splice(batch, key, inputs, extruded) : std::nullopt) {
            spliced = true;
            return std::move(*set);
        }
        grammar::BatchResult result = catalog_->expand(batch, inputs, key);
        if (result.failed) {
            std::lock_guard lock(failedMutex_);
            failedKeys_.insert(key.digest());
            const std::string why =
                result.issues.empty() ? "a batch cap was hit" : result.issues.back().first.detail;
            throw std::runtime_error("batch expansion hit a cap: " + why);
        }
        extruded = storeExtruded(batch, key, result.extruded);
        return std::move(result.terminals);
    };
    const cache::TerminalSetCache::SetPtr set = decoded_.getOrGenerate(key, [&] { return expand(true); });
    spliceBases_.remember(batch, key, inputs);
    if (kind == PayloadKind::TerminalSet) {
        auto bytes = std::make_shared<const std::vector<uint8_t>>(
            grammar::encodeTerminalSet(*set, options_.zstdLevel));
        terminalPayloads_.insert(key, bytes);
        metrics_.recordGeneration(spliced    ? "terminal_set_spliced"
                                  : expanded ? "terminal_set"
                                             : "terminal_set_encode",
                                  secondsSince(start));
        return {std::move(bytes), 200, {}, {}};
    }
    if (!extruded) extruded = extrudedPayloads_.peek(key); // made by the expansion this one waited for
    // The decoded tier had the terminals, or they were spliced without an extruded set to
    // splice into: only a whole expansion gives the extruded set.
    if (!extruded) expand(false);
    metrics_.recordGeneration("extruded_set", secondsSince(start));
    return {std::move(extruded), 200, {}, {}};
}

} // namespace hexlod::server
