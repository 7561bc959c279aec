// The bulk allocator's pool of released blocks: kept for reuse up to its limit, and a lowered
// limit frees what lies beyond it at once (a long-running service bounds its memory so); a
// request takes the smallest pooled block that holds it, unless that one is over a quarter
// larger; a block tells the bytes it holds, which memory budgets count.
#include "hexlod/grammar/bulk_allocator.h"

#include <gtest/gtest.h>

#include <vector>

namespace hexlod::grammar {
namespace {

using BulkWords = std::vector<uint32_t, BulkAllocator<uint32_t>>;
constexpr size_t kMiB = size_t(1) << 20;

BulkWords wordsOfMiB(size_t mebibytes) {
    BulkWords words(mebibytes * kMiB / sizeof(uint32_t));
    words[0] = 1;
    return words;
}

// Starts every test from an empty pool: other tests in the process may have left blocks.
class BulkAllocatorTest : public ::testing::Test {
protected:
    void SetUp() override {
        setBulkPoolLimit(0);
        setBulkPoolLimit(size_t(256) << 20);
    }
    void TearDown() override { setBulkPoolLimit(size_t(2) << 30); }
};

TEST_F(BulkAllocatorTest, ReleasedBlocksArePooledUpToTheLimit) {
    ASSERT_EQ(bulkPoolBytes(), 0u);
    { const BulkWords big = wordsOfMiB(12); }
    EXPECT_EQ(bulkPoolBytes(), 12 * kMiB);
    setBulkPoolLimit(0);
    EXPECT_EQ(bulkPoolBytes(), 0u);
    { const BulkWords big = wordsOfMiB(12); }
    EXPECT_EQ(bulkPoolBytes(), 0u); // nothing kept above a zero limit
}

TEST_F(BulkAllocatorTest, ASmallerRequestTakesTheSmallestBlockThatHoldsIt) {
    const uint32_t* sixteen = nullptr;
    const uint32_t* twenty = nullptr;
    {
        const BulkWords a = wordsOfMiB(16), b = wordsOfMiB(20), c = wordsOfMiB(8);
        sixteen = a.data();
        twenty = b.data();
    }
    ASSERT_EQ(bulkPoolBytes(), 44 * kMiB);
    {
        // 14 MiB: the 8 MiB block is too small, the 16 and 20 MiB ones hold it; 16 is nearer.
        const BulkWords reused = wordsOfMiB(14);
        EXPECT_EQ(reused.data(), sixteen);
        EXPECT_EQ(bulkPoolBytes(), 28 * kMiB);
    }
    // Back at its own size, not the 14 MiB the vector asked for.
    EXPECT_EQ(bulkPoolBytes(), 44 * kMiB);
    {
        const BulkWords a = wordsOfMiB(16), b = wordsOfMiB(17);
        EXPECT_EQ(a.data(), sixteen);
        EXPECT_EQ(b.data(), twenty); // 17 MiB is 18 in whole huge pages: 20 is within a quarter
    }
    EXPECT_EQ(bulkPoolBytes(), 44 * kMiB);
}

TEST_F(BulkAllocatorTest, ABlockOverAQuarterLargerIsNotTaken) {
    { const BulkWords big = wordsOfMiB(32); }
    ASSERT_EQ(bulkPoolBytes(), 32 * kMiB);
    {
        const BulkWords small = wordsOfMiB(24); // 32 is a third more than 24
        EXPECT_EQ(bulkPoolBytes(), 32 * kMiB);
    }
    EXPECT_EQ(bulkPoolBytes(), 56 * kMiB);
    {
        const BulkWords exact = wordsOfMiB(26); // 32 is under 26 and a quarter (32.5)
        EXPECT_EQ(bulkPoolBytes(), 24 * kMiB);
    }
}

TEST_F(BulkAllocatorTest, ABlockReportsTheBytesItHolds) {
    { const BulkWords big = wordsOfMiB(32); }
    {
        const BulkWords reused = wordsOfMiB(26); // takes the 32 MiB block
        EXPECT_EQ(bulkBlockBytes(reused.data(), 26 * kMiB), 32 * kMiB);
        const BulkWords fresh(17 * kMiB / sizeof(uint32_t) + 1); // whole huge pages: 18 MiB
        EXPECT_EQ(bulkBlockBytes(fresh.data(), fresh.capacity() * sizeof(uint32_t)), 18 * kMiB);
        const BulkWords small = wordsOfMiB(1); // the heap's, below the bulk threshold
        EXPECT_EQ(bulkBlockBytes(small.data(), kMiB), kMiB);
    }
    EXPECT_EQ(bulkBlockBytes(nullptr, 0), 0u);
}

} // namespace
} // namespace hexlod::grammar
