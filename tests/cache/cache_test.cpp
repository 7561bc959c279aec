// The terminal-set cache: keys that change exactly with a batch's inputs, LRU eviction
// within a byte budget (a property test under random access and pins), one generation per
// key under concurrency, and a disk tier that survives restarts and shrugs off corruption.
#include "hexlod/cache/batch_key.h"
#include "hexlod/cache/terminal_set_cache.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

#include <unistd.h>

namespace hexlod::cache {
namespace {

namespace fs = std::filesystem;
using grammar::BuildingInput;
using grammar::TerminalSet;

std::vector<BuildingInput> buildings(uint32_t count) {
    std::vector<BuildingInput> out(count);
    for (uint32_t i = 0; i < count; ++i) {
        out[i].id = 100 + i;
        out[i].footprint = {{0.0, 0.0}, {10.0 + i, 0.0}, {10.0 + i, 8.0}, {0.0, 8.0}};
        out[i].parameters = {4.0f, 3.0f, 2.8f};
    }
    return out;
}

TEST(BatchKey, ChangesExactlyWithTheParametersAndUndoRestoresIt) {
    std::vector<BuildingInput> batch = buildings(5);
    const uint64_t before = hashBatchParameters(batch);
    EXPECT_EQ(hashBatchParameters(batch), before);
    batch[2].parameters[1] = 3.5f;
    const uint64_t edited = hashBatchParameters(batch);
    EXPECT_NE(edited, before);
    batch[2].parameters[1] = 3.0f;
    EXPECT_EQ(hashBatchParameters(batch), before);
    batch[4].footprint[1].x += 0.001;
    EXPECT_NE(hashBatchParameters(batch), before);
    batch[4].footprint[1].x -= 0.001;
    EXPECT_NE(hashBatchParameters(batch, 7), before); // another scene seed
    // Moving a value from one building to another is an edit too.
    std::vector<BuildingInput> swapped = buildings(5);
    std::swap(swapped[0].parameters[0], swapped[1].parameters[1]);
    EXPECT_NE(hashBatchParameters(swapped), before);
}

TEST(BatchKey, IgnoresTheOrderOfBuildings) {
    std::vector<BuildingInput> batch = buildings(40);
    const uint64_t sorted = hashBatchParameters(batch);
    std::mt19937 rng(3);
    for (int i = 0; i < 5; ++i) {
        std::shuffle(batch.begin(), batch.end(), rng);
        EXPECT_EQ(hashBatchParameters(batch), sorted);
    }
}

// An edit of one building changes the key of its batch and of no other batch.
TEST(BatchKey, AnEditTouchesOnlyTheBatchesHoldingTheEditedBuilding) {
    std::vector<BuildingInput> all = buildings(12);
    const auto keysOf = [&] {
        std::vector<BatchKey> keys;
        for (int cell = 0; cell < 3; ++cell) {
            const std::span<const BuildingInput> part(all.data() + 4 * cell, 4);
            keys.push_back({{cell, -cell}, 0, 0xabcdull, hashBatchParameters(part)});
        }
        return keys;
    };
    const std::vector<BatchKey> before = keysOf();
    all[5].parameters[0] = 6.0f; // building 105, in the second batch
    const std::vector<BatchKey> after = keysOf();
    EXPECT_EQ(after[0], before[0]);
    EXPECT_FALSE(after[1] == before[1]);
    EXPECT_EQ(after[2], before[2]);
    EXPECT_NE(after[1].digest(), before[1].digest());
}

TEST(BatchKey, DigestIsStableAndItsHexIsFileNameSafe) {
    const BatchKey key{{-3, 7}, 1, 0x1122334455667788ull, 0x99aabbccddeeff00ull};
    EXPECT_EQ(key.hex(), hexDigest(key.digest()));
    EXPECT_EQ(key.hex().size(), 16u);
    EXPECT_EQ(key.hex().find_first_not_of("0123456789abcdef"), std::string::npos);
    // Pinned: disk files and URLs are named by it, so it must not change between builds.
    EXPECT_EQ(key.hex(), "e36ca1cdcbb52882");
    BatchKey other = key;
    other.cell.r = 8;
    EXPECT_NE(other.digest(), key.digest());
    EXPECT_NE(BatchKeyHash{}(other), BatchKeyHash{}(key));
}

// A set of `records` terminals whose building ids carry `tag`, so a test can tell sets apart.
TerminalSet makeSet(size_t records, uint32_t tag) {
    TerminalSet set;
    set.header.cell = {int32_t(tag), 1};
    set.countPerShape = {uint32_t(records)};
    set.records.resize(records);
    for (size_t i = 0; i < records; ++i)
        set.records[i] = grammar::packTerminal({float(i), float(tag), 0.5f}, {1, 0, 0}, {0, 0, 1}, {0, -1, 0},
                                               {1.0f, 2.0f}, 0.1f, 0, tag);
    return set;
}
uint64_t bytesOf(size_t records) {
    return makeSet(records, 0).byteSize();
}
BatchKey keyOf(int i) {
    return {{i, 2 * i}, 0, 0x5eedull, uint64_t(i) * 31};
}
uint32_t tagOf(const TerminalSet& set) {
    return set.records.empty() ? uint32_t(set.header.cell.q) : set.records[0].building;
}

// A set decoded into a released block up to a quarter larger than its records holds that whole
// block (bulk_allocator.h): the budget counts it, not the records alone.
TEST(TerminalSetCache, CountsTheWholeBlockASetsRecordsHold) {
    grammar::setBulkPoolLimit(0); // from an empty pool: other tests may have left blocks
    grammar::setBulkPoolLimit(size_t(256) << 20);
    constexpr size_t kBlock = size_t(32) << 20;
    using Records = std::vector<grammar::TerminalRecord, grammar::BulkAllocator<grammar::TerminalRecord>>;
    // 26 MiB of records in a released 32 MiB block.
    const auto setInABlock = [&] {
        { const Records released(kBlock / sizeof(grammar::TerminalRecord)); }
        return makeSet((size_t(26) << 20) / sizeof(grammar::TerminalRecord), 7);
    };
    TerminalSet set = setInABlock();
    const uint64_t held = set.heldBytes();
    EXPECT_EQ(held, set.byteSize() + kBlock - set.records.size() * sizeof(grammar::TerminalRecord));
    {
        TerminalSetCache cache(
            {.memoryBudgetBytes = uint64_t(1) << 30, .diskBudgetBytes = 0, .diskPath = {}});
        cache.insert(keyOf(1), std::move(set));
        EXPECT_EQ(cache.stats().memoryBytes, held);
    }
    // A budget its records fit in but its block does not keeps nothing.
    set = setInABlock();
    ASSERT_EQ(set.heldBytes(), held);
    TerminalSetCache tight({.memoryBudgetBytes = held - 1, .diskBudgetBytes = 0, .diskPath = {}});
    ASSERT_LT(set.byteSize(), held - 1);
    tight.insert(keyOf(1), std::move(set));
    EXPECT_EQ(tight.stats().memoryEntries, 0u);
    grammar::setBulkPoolLimit(size_t(2) << 30);
}

TEST(TerminalSetCache, EvictsTheLeastRecentlyUsedFirst) {
    TerminalSetCache cache({.memoryBudgetBytes = 3 * bytesOf(100), .diskBudgetBytes = 0, .diskPath = {}});
    for (int i = 0; i < 3; ++i) cache.insert(keyOf(i), makeSet(100, i));
    EXPECT_NE(cache.find(keyOf(0)), nullptr); // 0 is now the most recent; 1 the least
    cache.insert(keyOf(3), makeSet(100, 3));
    EXPECT_EQ(cache.find(keyOf(1)), nullptr);
    cache.insert(keyOf(4), makeSet(100, 4)); // evicts 2
    EXPECT_EQ(cache.find(keyOf(2)), nullptr);
    for (int i : {0, 3, 4}) {
        const auto set = cache.find(keyOf(i));
        ASSERT_NE(set, nullptr) << i;
        EXPECT_EQ(tagOf(*set), uint32_t(i));
    }
    const CacheStats s = cache.stats();
    EXPECT_EQ(s.evictions, 2u);
    EXPECT_EQ(s.memoryEntries, 3u);
    EXPECT_EQ(s.memoryBytes, 3 * bytesOf(100));
    EXPECT_EQ(s.lookups, 6u);
    EXPECT_EQ(s.memoryHits, 4u);
    EXPECT_EQ(s.misses, 2u);
    EXPECT_EQ(s.insertions, 5u);
}

TEST(TerminalSetCache, SupersededEntriesGoFirstLongestSupersededFirst) {
    TerminalSetCache cache({.memoryBudgetBytes = 4 * bytesOf(100), .diskBudgetBytes = 0, .diskPath = {}});
    for (int i = 0; i < 4; ++i) cache.insert(keyOf(i), makeSet(100, i));
    cache.markSuperseded(keyOf(2));
    cache.markSuperseded(keyOf(1));
    cache.markSuperseded(keyOf(1)); // twice: no change
    cache.markSuperseded(keyOf(9)); // not cached: ignored
    cache.insert(keyOf(4), makeSet(100, 4));
    EXPECT_EQ(cache.findInMemory(keyOf(2)), nullptr) << "superseded longest ago";
    cache.markCurrent(keyOf(1)); // an undo back to it: current and most recent again
    cache.insert(keyOf(5), makeSet(100, 5));
    EXPECT_EQ(cache.findInMemory(keyOf(0)), nullptr) << "the least recently used current entry";
    for (int i : {1, 3, 4, 5}) EXPECT_NE(cache.findInMemory(keyOf(i)), nullptr) << i;
    // A hit makes a superseded entry current too.
    cache.markSuperseded(keyOf(3));
    EXPECT_NE(cache.findInMemory(keyOf(3)), nullptr);
    cache.insert(keyOf(6), makeSet(100, 6));
    EXPECT_EQ(cache.findInMemory(keyOf(1)), nullptr);
    EXPECT_NE(cache.findInMemory(keyOf(3)), nullptr);
}

TEST(TerminalSetCache, PinnedEntriesSurviveAndTheOverflowIsReported) {
    TerminalSetCache cache({.memoryBudgetBytes = 2 * bytesOf(100), .diskBudgetBytes = 0, .diskPath = {}});
    cache.insert(keyOf(0), makeSet(100, 0));
    cache.insert(keyOf(1), makeSet(100, 1));
    auto pin0 = cache.find(keyOf(0));
    auto pin1 = cache.find(keyOf(1));
    cache.insert(keyOf(2), makeSet(100, 2)); // nothing evictable: the new set is not kept
    EXPECT_EQ(cache.find(keyOf(2)), nullptr);
    // getOrGenerate keeps what it returns while the caller holds it, over budget.
    auto pin3 = cache.getOrGenerate(keyOf(3), [] { return makeSet(100, 3); });
    CacheStats s = cache.stats();
    EXPECT_EQ(s.memoryBytes, 3 * bytesOf(100));
    EXPECT_EQ(s.pinnedBytes, 3 * bytesOf(100));
    EXPECT_EQ(tagOf(*cache.find(keyOf(3))), 3u);
    pin0.reset();
    pin3.reset();
    cache.trim(); // 0 is older than 3 and unpinned: it goes first, and that suffices
    s = cache.stats();
    EXPECT_EQ(s.memoryBytes, 2 * bytesOf(100));
    EXPECT_EQ(s.pinnedBytes, bytesOf(100));
    EXPECT_EQ(cache.find(keyOf(0)), nullptr);
    EXPECT_NE(cache.find(keyOf(3)), nullptr);
}

// Random inserts, finds, generations and superseded or current marks with random sizes, with
// and without pins held:
// resident bytes never exceed the budget when nothing is pinned, never exceed budget plus
// pinned bytes otherwise, every hit is the latest set of its key, and the counters add up.
void randomAccess(bool withPins, uint32_t seed) {
    const uint64_t budget = 40 * bytesOf(64);
    TerminalSetCache cache({.memoryBudgetBytes = budget, .diskBudgetBytes = 0, .diskPath = {}});
    std::mt19937 rng(seed);
    std::vector<TerminalSetCache::SetPtr> pins;
    std::vector<uint32_t> latest(64, 0); // version last stored per key; 0: never
    uint32_t version = 0;
    for (int op = 0; op < 3000; ++op) {
        const int k = int(rng() % 64);
        const size_t records = rng() % 128;
        const uint32_t choice = rng() % 12;
        TerminalSetCache::SetPtr got;
        if (choice == 10) {
            cache.markSuperseded(keyOf(k));
        } else if (choice == 11) {
            cache.markCurrent(keyOf(k));
        } else if (choice < 4) {
            latest[k] = ++version;
            cache.insert(keyOf(k), makeSet(records, version));
        } else if (choice < 8) {
            got = cache.find(keyOf(k));
        } else {
            got = cache.getOrGenerate(keyOf(k), [&] {
                latest[k] = ++version;
                return makeSet(records, version);
            });
        }
        if (got) {
            EXPECT_EQ(tagOf(*got), latest[k]) << "op " << op;
        }
        if (withPins && got && rng() % 3 == 0) pins.push_back(got);
        if (!pins.empty() && rng() % 4 == 0) pins.erase(pins.begin() + long(rng() % pins.size()));
        got.reset();
        if (pins.empty()) cache.trim(); // drops what the last release unpinned
        const CacheStats s = cache.stats();
        if (pins.empty()) {
            ASSERT_LE(s.memoryBytes, budget) << "op " << op;
        }
        ASSERT_LE(s.memoryBytes, budget + s.pinnedBytes) << "op " << op;
        ASSERT_EQ(s.lookups, s.hits + s.misses);
        ASSERT_EQ(s.hits, s.memoryHits + s.diskHits + s.sharedGenerations);
        ASSERT_LE(s.memoryEntries + s.evictions, s.insertions);
    }
    const CacheStats s = cache.stats();
    EXPECT_GT(s.evictions, 100u);
    EXPECT_GT(s.memoryHits, 100u);
    EXPECT_GT(s.generations, 50u);
}

TEST(TerminalSetCache, RandomAccessKeepsTheBudgetWithoutPins) {
    randomAccess(false, 11);
}
TEST(TerminalSetCache, RandomAccessKeepsTheBudgetWithPins) {
    randomAccess(true, 12);
}

TEST(TerminalSetCache, ConcurrentCallersGenerateAMissingKeyOnce) {
    TerminalSetCache cache({.memoryBudgetBytes = uint64_t(1) << 30, .diskBudgetBytes = 0, .diskPath = {}});
    std::atomic<int> calls{0};
    std::atomic<bool> go{false};
    std::vector<TerminalSetCache::SetPtr> results(8);
    std::vector<std::thread> threads;
    for (int t = 0; t < 8; ++t)
        threads.emplace_back([&, t] {
            while (!go) std::this_thread::yield();
            results[t] = cache.getOrGenerate(keyOf(9), [&] {
                ++calls;
                std::this_thread::sleep_for(std::chrono::milliseconds(100));
                return makeSet(1000, 9);
            });
        });
    go = true;
    for (std::thread& t : threads) t.join();
    EXPECT_EQ(calls.load(), 1);
    for (const auto& r : results) EXPECT_EQ(r, results[0]);
    const CacheStats s = cache.stats();
    EXPECT_EQ(s.generations, 1u);
    EXPECT_EQ(s.misses, 1u);
    EXPECT_EQ(s.sharedGenerations + s.memoryHits, 7u);
    EXPECT_GE(s.generationSecondsMax, 0.09);
    EXPECT_EQ(s.generationSecondsTotal, s.generationSecondsMax);
}

TEST(TerminalSetCache, AFailedGenerationReachesEveryWaiterAndCachesNothing) {
    TerminalSetCache cache({.memoryBudgetBytes = uint64_t(1) << 30, .diskBudgetBytes = 0, .diskPath = {}});
    const auto fail = []() -> TerminalSet { throw std::runtime_error("grammar broke"); };
    EXPECT_THROW(cache.getOrGenerate(keyOf(1), fail), std::runtime_error);
    EXPECT_EQ(cache.find(keyOf(1)), nullptr);
    EXPECT_EQ(tagOf(*cache.getOrGenerate(keyOf(1), [] { return makeSet(3, 1); })), 1u);
}

// A fresh folder per test, under gtest's temporary directory.
fs::path freshFolder(const std::string& name) {
    const fs::path folder =
        fs::path(::testing::TempDir()) / ("hexlod_cache_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(folder);
    return folder;
}

CacheOptions diskOptions(const fs::path& folder, uint64_t memoryBudget,
                         uint64_t diskBudget = uint64_t(1) << 30) {
    return {.memoryBudgetBytes = memoryBudget, .diskBudgetBytes = diskBudget, .diskPath = folder.string()};
}

fs::path fileOf(const fs::path& folder, const BatchKey& key) {
    return folder / (key.hex() + ".hxc");
}

TEST(DiskTier, PersistsAcrossCacheInstances) {
    const fs::path folder = freshFolder("persist");
    {
        TerminalSetCache cache(diskOptions(folder, uint64_t(1) << 30));
        for (int i = 0; i < 3; ++i) cache.insert(keyOf(i), makeSet(500, i));
        cache.flushDisk();
        EXPECT_EQ(cache.stats().diskFiles, 3u);
    }
    TerminalSetCache cache(diskOptions(folder, uint64_t(1) << 30));
    CacheStats s = cache.stats();
    EXPECT_EQ(s.diskFiles, 3u);
    EXPECT_EQ(s.memoryEntries, 0u);
    const auto loaded = cache.find(keyOf(1));
    ASSERT_NE(loaded, nullptr);
    const TerminalSet expected = makeSet(500, 1);
    EXPECT_EQ(
        std::memcmp(loaded->records.data(), expected.records.data(), 500 * sizeof(grammar::TerminalRecord)),
        0);
    EXPECT_EQ(loaded->countPerShape, expected.countPerShape);
    EXPECT_EQ(cache.find(keyOf(1)), loaded); // promoted: the second find is a memory hit
    int generated = 0;
    cache.getOrGenerate(keyOf(2), [&] { return ++generated, makeSet(1, 2); });
    EXPECT_EQ(generated, 0);
    s = cache.stats();
    EXPECT_EQ(s.diskHits, 2u);
    EXPECT_EQ(s.memoryHits, 1u);
    EXPECT_EQ(s.misses, 0u);
    EXPECT_EQ(s.generations, 0u);
    fs::remove_all(folder);
}

TEST(DiskTier, EvictsTheLeastRecentlyUsedFileOverBudget) {
    const fs::path folder = freshFolder("evict");
    uint64_t fileBytes = 0;
    {
        TerminalSetCache probe(diskOptions(folder, 0));
        probe.insert(keyOf(0), makeSet(2000, 0));
        probe.flushDisk();
        fileBytes = fs::file_size(fileOf(folder, keyOf(0)));
    }
    TerminalSetCache cache(diskOptions(folder, 0, 2 * fileBytes + fileBytes / 2)); // memory holds nothing
    cache.insert(keyOf(1), makeSet(2000, 1));
    cache.flushDisk();
    EXPECT_NE(cache.find(keyOf(0)), nullptr); // 1 is now the least recently used file
    cache.insert(keyOf(2), makeSet(2000, 2));
    cache.flushDisk();
    EXPECT_FALSE(fs::exists(fileOf(folder, keyOf(1))));
    EXPECT_TRUE(fs::exists(fileOf(folder, keyOf(0))));
    EXPECT_TRUE(fs::exists(fileOf(folder, keyOf(2))));
    EXPECT_EQ(cache.find(keyOf(1)), nullptr);
    const CacheStats s = cache.stats();
    EXPECT_EQ(s.diskEvictions, 1u);
    EXPECT_EQ(s.diskFiles, 2u);
    EXPECT_LE(s.diskBytes, 2 * fileBytes + fileBytes / 2);
    EXPECT_EQ(s.memoryBytes, 0u);
    fs::remove_all(folder);
}

enum class Damage { Truncate, FlipByte, WrongVersion, OtherKeysName };

// Damages key 0's file while the cache runs (memory budget 0: every find reads the disk),
// then expects a miss, the file deleted, a regeneration and a good file again.
void expectDamageIsRegenerated(Damage damage, const std::string& name) {
    const fs::path folder = freshFolder(name);
    TerminalSetCache cache(diskOptions(folder, 0));
    cache.insert(keyOf(0), makeSet(300, 0));
    cache.insert(keyOf(1), makeSet(300, 1));
    cache.flushDisk();
    const fs::path file = fileOf(folder, keyOf(0));
    const uint64_t size = fs::file_size(file);
    BatchKey damagedKey = keyOf(0);
    if (damage == Damage::Truncate) {
        fs::resize_file(file, size / 2);
    } else if (damage == Damage::OtherKeysName) {
        fs::rename(file, fileOf(folder, keyOf(1))); // key 1's name, key 0's content
        damagedKey = keyOf(1);
    } else {
        std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
        const uint64_t offset = damage == Damage::FlipByte ? size - 20 : 4; // 4: the version
        f.seekp(std::streamoff(offset));
        const char value = damage == Damage::FlipByte ? char(0x5a) : char(2);
        f.write(&value, 1);
    }
    EXPECT_EQ(cache.find(damagedKey), nullptr);
    EXPECT_FALSE(fs::exists(fileOf(folder, damagedKey)));
    CacheStats s = cache.stats();
    EXPECT_EQ(s.corruptFilesDropped, 1u);
    EXPECT_EQ(s.diskHits, 0u);
    int generated = 0;
    auto set = cache.getOrGenerate(damagedKey, [&] {
        ++generated;
        return makeSet(300, uint32_t(damagedKey.cell.q));
    });
    EXPECT_EQ(generated, 1);
    EXPECT_EQ(tagOf(*set), uint32_t(damagedKey.cell.q));
    set.reset();
    cache.flushDisk(); // written and unpinned, so out of memory: the next find reads the disk
    EXPECT_TRUE(fs::exists(fileOf(folder, damagedKey)));
    EXPECT_NE(cache.find(damagedKey), nullptr); // the rewritten file reads back
    s = cache.stats();
    EXPECT_EQ(s.diskHits, 1u);
    EXPECT_EQ(s.corruptFilesDropped, 1u);
    fs::remove_all(folder);
}

TEST(DiskTier, ATruncatedFileIsDroppedAndRegenerated) {
    expectDamageIsRegenerated(Damage::Truncate, "truncate");
}
TEST(DiskTier, AFlippedByteIsDroppedAndRegenerated) {
    expectDamageIsRegenerated(Damage::FlipByte, "flip");
}
TEST(DiskTier, AnotherVersionIsDroppedAndRegenerated) {
    expectDamageIsRegenerated(Damage::WrongVersion, "version");
}
TEST(DiskTier, AFileUnderAnotherKeysNameIsDroppedAndRegenerated) {
    expectDamageIsRegenerated(Damage::OtherKeysName, "rename");
}

// Sets go to disk on the writer's thread: flushDisk() waits for them and unpins them, and
// whatever is still queued when the cache goes is written before it goes.
TEST(DiskTier, QueuedWritesAreFlushedOrFinishedOnDestruction) {
    const fs::path folder = freshFolder("queued");
    {
        TerminalSetCache cache(diskOptions(folder, 0)); // memory keeps only what is pinned
        const auto generate = [&](int i) {
            int generated = 0;
            cache.getOrGenerate(keyOf(i), [&] { return ++generated, makeSet(4000, uint32_t(i)); });
            EXPECT_EQ(generated, 1);
        };
        for (int i = 0; i < 8; ++i) generate(i);
        cache.flushDisk();
        CacheStats s = cache.stats();
        EXPECT_EQ(s.diskFiles, 8u);
        EXPECT_EQ(s.memoryEntries, 0u);           // written, so unpinned and trimmed to the budget
        for (int i = 8; i < 16; ++i) generate(i); // left queued for the destructor
        s = cache.stats();
        EXPECT_EQ(s.misses, 16u);
        EXPECT_EQ(s.generations, 16u);
    }
    TerminalSetCache cache(diskOptions(folder, 0));
    EXPECT_EQ(cache.stats().diskFiles, 16u);
    for (int i = 0; i < 16; ++i) {
        const auto set = cache.find(keyOf(i));
        ASSERT_NE(set, nullptr);
        EXPECT_EQ(tagOf(*set), uint32_t(i));
    }
    EXPECT_EQ(cache.stats().diskHits, 16u);
    fs::remove_all(folder);
}

// At start the cache adopts good files and deletes its own broken ones and leftovers of
// interrupted writes; files it did not write are none of its business.
TEST(DiskTier, StartupAdoptsGoodFilesAndDeletesGarbage) {
    const fs::path folder = freshFolder("startup");
    {
        TerminalSetCache cache(diskOptions(folder, 0));
        cache.insert(keyOf(0), makeSet(50, 0));
        cache.insert(keyOf(1), makeSet(50, 1));
    }
    fs::resize_file(fileOf(folder, keyOf(1)), 30);                         // shorter than a header
    fs::copy_file(fileOf(folder, keyOf(0)), fileOf(folder, keyOf(2)));     // a name that lies
    std::ofstream(folder / (keyOf(3).hex() + ".17.tmp")) << "interrupted"; // a crashed write
    std::ofstream(folder / "notes.txt") << "not ours";
    TerminalSetCache cache(diskOptions(folder, 0));
    const CacheStats s = cache.stats();
    EXPECT_EQ(s.diskFiles, 1u);
    EXPECT_EQ(s.corruptFilesDropped, 2u);
    EXPECT_FALSE(fs::exists(fileOf(folder, keyOf(1))));
    EXPECT_FALSE(fs::exists(fileOf(folder, keyOf(2))));
    EXPECT_FALSE(fs::exists(folder / (keyOf(3).hex() + ".17.tmp")));
    EXPECT_TRUE(fs::exists(folder / "notes.txt"));
    EXPECT_NE(cache.find(keyOf(0)), nullptr);
    fs::remove_all(folder);
}

} // namespace
} // namespace hexlod::cache
