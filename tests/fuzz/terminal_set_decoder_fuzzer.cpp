// libFuzzer target for the terminal-set decoder (docs/protocol.md, "Terminal set, version 1"):
// arbitrary bytes must be rejected with a reason or decode to a set whose records are grouped
// by shape as its counts say and that re-encodes to a payload decoding to the same bits. With
// ASan this checks that no input reads out of bounds or allocates what its header merely
// claims (-rss_limit_mb catches the latter).
#include "fuzz_check.h"

#include "hexlod/grammar/terminal_set_codec.h"

#include <cstring>

using hexlod::fuzz::check;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace hexlod::grammar;
    TerminalSet set;
    std::string error;
    if (!decodeTerminalSet({data, size}, set, error)) {
        check(!error.empty());
        return 0;
    }
    uint64_t total = 0;
    for (const uint32_t count : set.countPerShape) total += count;
    check(total == set.records.size());
    size_t next = 0;
    for (uint16_t shape = 0; shape < set.countPerShape.size(); ++shape)
        for (uint32_t i = 0; i < set.countPerShape[shape]; ++i)
            check((set.records[next++].shapeAndDepth & 0xffffu) == shape);
    const std::vector<uint8_t> again = encodeTerminalSet(set);
    TerminalSet set2;
    check(decodeTerminalSet(again, set2, error));
    check(set2.records.size() == set.records.size() && set2.countPerShape == set.countPerShape);
    check(set.records.empty() || std::memcmp(set.records.data(), set2.records.data(),
                                             set.records.size() * sizeof(set.records[0])) == 0);
    return 0;
}
