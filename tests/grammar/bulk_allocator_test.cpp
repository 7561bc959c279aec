// The bulk allocator's pool of released blocks: kept for reuse up to its limit, and a lowered
// limit frees what lies beyond it at once (a long-running service bounds its memory so).
#include "hexlod/grammar/bulk_allocator.h"

#include <gtest/gtest.h>

#include <vector>

namespace hexlod::grammar {
namespace {

TEST(BulkAllocator, ReleasedBlocksArePooledUpToTheLimit) {
    setBulkPoolLimit(0); // start empty: other tests may have left blocks
    setBulkPoolLimit(size_t(64) << 20);
    const size_t before = bulkPoolBytes();
    ASSERT_EQ(before, 0u);
    {
        std::vector<uint32_t, BulkAllocator<uint32_t>> big(size_t(3) << 20); // 12 MiB: a bulk block
        big[0] = 1;
    }
    EXPECT_EQ(bulkPoolBytes(), before + (size_t(12) << 20));
    setBulkPoolLimit(0);
    EXPECT_EQ(bulkPoolBytes(), 0u);
    {
        std::vector<uint32_t, BulkAllocator<uint32_t>> big(size_t(3) << 20);
        big[0] = 1;
    }
    EXPECT_EQ(bulkPoolBytes(), 0u); // nothing kept above a zero limit
    setBulkPoolLimit(size_t(2) << 30);
}

} // namespace
} // namespace hexlod::grammar
