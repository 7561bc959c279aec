// The terminal-set codec: byte-exact round trips on a real batch, a size bound, golden bytes
// that pin format version 1, and rejection of every truncation, bit flip and lying header.
#include "hexlod/grammar/batch_expander.h"
#include "hexlod/grammar/terminal_set_codec.h"
#include "hexlod/scene/demo_footprints.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <functional>

namespace hexlod::grammar {
namespace {

bool sameBytes(const TerminalSet& a, const TerminalSet& b) {
    return a.records.size() == b.records.size() && a.countPerShape == b.countPerShape &&
           std::memcmp(&a.header, &b.header, sizeof(a.header)) == 0 &&
           (a.records.empty() || // memcmp must not see the null data() of an empty vector
            std::memcmp(a.records.data(), b.records.data(), a.records.size() * sizeof(TerminalRecord)) == 0);
}

TerminalSet residentialBatch(uint32_t buildings) {
    DiagnosticList diagnostics;
    const CompiledGrammar g =
        compileGrammarFile(HEXLOD_CONFIGS_DIR "/grammars/residential.grammar", diagnostics);
    EXPECT_FALSE(diagnostics.hasErrors()) << diagnostics.formatAll();
    std::vector<BuildingInput> input = scene::makeDemoFootprints({buildings, 42, 60.0});
    for (BuildingInput& b : input)
        b.parameters = resolveParameters(g, scene::demoParameterOverrides(g, 42, b.id), diagnostics);
    BatchInput batch;
    batch.grammar = &g;
    batch.buildings = input;
    batch.settings.seed = 42;
    batch.settings.cellOrigin = {120.0, -80.0, 0.0};
    batch.cell = {3, -2};
    batch.grammarIndex = 1;
    BatchResult result = expandBatch(batch);
    result.terminals.header.key = 0x0123456789abcdefull;
    return std::move(result.terminals);
}

double secondsFor(const std::function<void()>& work, int repeats) {
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < repeats; ++i) work();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / repeats;
}

TEST(TerminalSetCodec, RoundTripsARealBatchByteExactlyAndCompresses) {
    const TerminalSet set = residentialBatch(40);
    ASSERT_GT(set.records.size(), 10000u);
    std::vector<uint8_t> encoded;
    const double encodeSeconds = secondsFor([&] { encoded = encodeTerminalSet(set); }, 3);
    TerminalSet decoded;
    std::string error;
    bool ok = false;
    const double decodeSeconds = secondsFor([&] { ok = decodeTerminalSet(encoded, decoded, error); }, 3);
    ASSERT_TRUE(ok) << error;
    EXPECT_TRUE(sameBytes(set, decoded));

    const double bytesPerTerminal = double(encoded.size()) / double(set.records.size());
    const double megabytes = double(set.byteSize()) / 1e6;
    std::printf("[ residential ] %zu terminals, %zu bytes encoded: %.2f B/terminal (raw 32), "
                "encode %.0f MB/s, decode %.0f MB/s\n",
                set.records.size(), encoded.size(), bytesPerTerminal, megabytes / encodeSeconds,
                megabytes / decodeSeconds);
    // Measured 3.2 B/terminal at zstd level 3; the bound leaves room for grammar changes.
    EXPECT_LT(bytesPerTerminal, 6.0);
}

TEST(TerminalSetCodec, RoundTripsEmptyAndShapeGappedSets) {
    TerminalSet empty;
    TerminalSet decoded;
    std::string error;
    ASSERT_TRUE(decodeTerminalSet(encodeTerminalSet(empty), decoded, error)) << error;
    EXPECT_TRUE(sameBytes(empty, decoded));

    TerminalSet gapped; // shapes 0 and 2 unused
    gapped.countPerShape = {0, 2, 0, 1};
    gapped.records.resize(3);
    for (size_t i = 0; i < 3; ++i) {
        gapped.records[i] = packTerminal({float(i), -1.5f, 1e7f}, {1, 0, 0}, {0, 0, 1}, {0, -1, 0},
                                         {2.0f, 3.0f}, 0.25f, i < 2 ? 1 : 3, 7 + uint32_t(i));
    }
    ASSERT_TRUE(decodeTerminalSet(encodeTerminalSet(gapped, 19), decoded, error)) << error;
    EXPECT_TRUE(sameBytes(gapped, decoded));
}

// Three fixed records over two shapes. Changing the layout must change these bytes: then
// bump kTerminalSetFormatVersion and regenerate them.
TerminalSet goldenSet() {
    TerminalSet set;
    set.header.cell = {-3, 5};
    set.header.grammar = 2;
    set.header.grammarHash = 0x1122334455667788ull;
    set.header.key = 0x99aabbccddeeff00ull;
    set.header.cellOrigin[0] = 1000.5;
    set.header.cellOrigin[1] = -250.25;
    set.header.cellOrigin[2] = 12.0;
    set.countPerShape = {2, 1};
    set.records.resize(3);
    set.records[0] = {{1.0f, 2.0f, 3.0f}, 10, {0x00007fffu, 0x7fff0000u}, 0x40003c00u, 0x00000000u};
    set.records[1] = {{1.5f, 2.0f, 6.0f}, 10, {0x00007fffu, 0x7fff0000u}, 0x40003c00u, 0x00000000u};
    set.records[2] = {{-4.0f, 0.5f, 3.0f}, 11, {0x5a825a82u, 0x00000000u}, 0x3c003800u, 0x38000001u};
    return set;
}

const std::vector<uint8_t> kGolden = {
    // clang-format off
    // magic, version
    0x48, 0x58, 0x54, 0x31, 0x01, 0x00, 0x00, 0x00,
    // checksum
    0x52, 0xde, 0xab, 0x9f, 0xf5, 0x45, 0xe0, 0xd5,
    // cell q, r; grammar; reserved
    0xfd, 0xff, 0xff, 0xff, 0x05, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00,
    // grammar hash; key
    0x88, 0x77, 0x66, 0x55, 0x44, 0x33, 0x22, 0x11, 0x00, 0xff, 0xee, 0xdd,
    0xcc, 0xbb, 0xaa, 0x99,
    // cell origin
    0x00, 0x00, 0x00, 0x00, 0x00, 0x44, 0x8f, 0x40, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x48, 0x6f, 0xc0, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x28, 0x40,
    // record count; body bytes
    0x03, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x52, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00,
    // shape count; counts per shape
    0x02, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00,
    // zstd frame
    0x28, 0xb5, 0x2f, 0xfd, 0x20, 0x60, 0x4d, 0x02, 0x00, 0x54, 0x03, 0x00,
    0x00, 0x00, 0x7f, 0x00, 0x00, 0x80, 0x00, 0xff, 0xff, 0x7f, 0xfe, 0x00,
    0x00, 0x00, 0x80, 0x00, 0x00, 0x00, 0x00, 0xff, 0xff, 0xff, 0x01, 0x00,
    0x00, 0x80, 0x01, 0xff, 0xff, 0xff, 0x00, 0x14, 0x00, 0x00, 0x00, 0x02,
    0x7f, 0x82, 0x5a, 0x82, 0x5a, 0x00, 0x00, 0x00, 0x3c, 0x00, 0x40, 0x38,
    0x00, 0x3c, 0x00, 0x38, 0x07, 0x00, 0xb8, 0x25, 0xbb, 0x56, 0x62, 0x42,
    0xda, 0xe1, 0xfd, 0x69, 0x04, 0xa7, 0x95, 0x6f, 0x95, 0x31
    // clang-format on
};

TEST(TerminalSetCodec, GoldenBytesDecodeToTheHandBuiltSet) {
    TerminalSet decoded;
    std::string error;
    ASSERT_TRUE(decodeTerminalSet(kGolden, decoded, error)) << error;
    EXPECT_TRUE(sameBytes(goldenSet(), decoded));
}

TEST(TerminalSetCodec, EncodingMatchesTheGoldenBytes) {
    const std::vector<uint8_t> encoded = encodeTerminalSet(goldenSet());
    std::string hex;
    for (uint8_t byte : encoded) {
        char text[8];
        std::snprintf(text, sizeof(text), "0x%02x, ", byte);
        hex += text;
    }
    EXPECT_EQ(encoded, kGolden) << "encoded: " << hex;
}

// Every prefix of a small payload is rejected with a reason. A bit flip is rejected or, where
// zstd ignores the bit (reserved header bits, bit-stream padding), decodes to the very same
// set: never to different data.
TEST(TerminalSetCodec, RejectsEveryTruncationAndEveryHarmfulBitFlip) {
    const std::vector<uint8_t> good = encodeTerminalSet(goldenSet());
    TerminalSet decoded;
    std::string error;
    for (size_t length = 0; length < good.size(); ++length) {
        error.clear();
        EXPECT_FALSE(decodeTerminalSet(std::span(good.data(), length), decoded, error))
            << "length " << length;
        EXPECT_FALSE(error.empty());
    }
    size_t harmless = 0;
    for (size_t bit = 0; bit < good.size() * 8; ++bit) {
        std::vector<uint8_t> flipped = good;
        flipped[bit / 8] ^= uint8_t(1u << (bit % 8));
        error.clear();
        if (decodeTerminalSet(flipped, decoded, error)) {
            EXPECT_TRUE(sameBytes(goldenSet(), decoded)) << "bit " << bit;
            ++harmless;
        } else {
            EXPECT_FALSE(error.empty());
        }
    }
    EXPECT_LT(harmless, good.size()); // a handful of ignored bits, not whole fields
    std::vector<uint8_t> longer = good;
    longer.push_back(0);
    EXPECT_FALSE(decodeTerminalSet(longer, decoded, error));
    EXPECT_NE(error.find("trailing"), std::string::npos) << error;
}

void expectRejected(const std::vector<uint8_t>& payload, const std::string& reason) {
    TerminalSet decoded;
    std::string error;
    EXPECT_FALSE(decodeTerminalSet(payload, decoded, error));
    EXPECT_NE(error.find(reason), std::string::npos) << error;
}

template <typename T> std::vector<uint8_t> with(std::vector<uint8_t> payload, size_t offset, T value) {
    std::memcpy(payload.data() + offset, &value, sizeof(T));
    return payload;
}

TEST(TerminalSetCodec, RejectsForeignInputAndLyingHeadersWithAReason) {
    const std::vector<uint8_t> good = encodeTerminalSet(goldenSet());
    expectRejected(with<char>(good, 0, 'Z'), "bad magic");
    expectRejected(with<uint32_t>(good, 4, 2), "unsupported terminal-set version 2");
    expectRejected(with<uint64_t>(good, 72, 4), "sum to 3"); // record count
    expectRejected(with<uint64_t>(good, 72, uint64_t(1) << 40), "exceeds the limit");
    expectRejected(with<uint32_t>(good, kTerminalSetFixedHeaderBytes, 3), "sum to 4"); // counts
    expectRejected(with<uint32_t>(good, 88, 70000), "shape count");
    expectRejected(with<uint64_t>(good, 80, 1), "trailing bytes");
    expectRejected(with<uint64_t>(good, 80, 1u << 20), "truncated");
    // Counts that still sum right but move a record to another shape: the checksum sees it.
    std::vector<uint8_t> moved = with<uint32_t>(good, kTerminalSetFixedHeaderBytes, 1);
    expectRejected(with<uint32_t>(moved, kTerminalSetFixedHeaderBytes + 4, 2), "checksum mismatch");
    expectRejected(std::vector<uint8_t>(200, 0), "bad magic");
}

// A record count within the limit but far beyond what the frame holds must not be honoured
// with an allocation: decoding answers from the frame's real size.
TEST(TerminalSetCodec, ALyingRecordCountCostsNoHugeAllocation) {
    TerminalSet set;
    set.countPerShape = {kTerminalSetMaxRecords};
    std::vector<uint8_t> payload = encodeTerminalSet(set); // zero records, a count that lies
    TerminalSet decoded;
    std::string error;
    EXPECT_FALSE(decodeTerminalSet(payload, decoded, error));
    payload = with<uint64_t>(payload, 72, kTerminalSetMaxRecords);
    EXPECT_FALSE(decodeTerminalSet(payload, decoded, error));
    EXPECT_FALSE(error.empty());
}

// Decoding reuses a per-thread buffer for the decompressed body: after a large set has grown
// it, a small set still decodes exactly, and lying headers are still found.
TEST(TerminalSetCodec, DecodingAfterALargerSetIsUnchanged) {
    const TerminalSet large = residentialBatch(40);
    TerminalSet decoded;
    std::string error;
    ASSERT_TRUE(decodeTerminalSet(encodeTerminalSet(large), decoded, error)) << error;
    ASSERT_TRUE(sameBytes(large, decoded));
    const TerminalSet small = goldenSet();
    const std::vector<uint8_t> good = encodeTerminalSet(small);
    ASSERT_TRUE(decodeTerminalSet(good, decoded, error)) << error;
    EXPECT_TRUE(sameBytes(small, decoded));
    expectRejected(with<uint64_t>(good, 72, 4), "sum to 3");
    expectRejected(with<uint64_t>(good, 80, 1u << 20), "truncated");
    std::vector<uint8_t> moved = with<uint32_t>(good, kTerminalSetFixedHeaderBytes, 1);
    expectRejected(with<uint32_t>(moved, kTerminalSetFixedHeaderBytes + 4, 2), "checksum mismatch");
    // And the large one again, from a buffer the small one used last.
    ASSERT_TRUE(decodeTerminalSet(encodeTerminalSet(large), decoded, error)) << error;
    EXPECT_TRUE(sameBytes(large, decoded));
}

TEST(TerminalSetCodec, RejectsRecordsOutsideTheirShapeRun) {
    TerminalSet set = goldenSet();
    set.records[0].shapeAndDepth = 1; // shape 1 inside the run of shape 0
    TerminalSet decoded;
    std::string error;
    EXPECT_FALSE(decodeTerminalSet(encodeTerminalSet(set), decoded, error));
    EXPECT_NE(error.find("outside the run"), std::string::npos) << error;
}

TEST(TerminalSetCodec, PeekReadsTheHeaderAlone) {
    const std::vector<uint8_t> good = encodeTerminalSet(goldenSet());
    TerminalSetPayloadInfo info;
    std::string error;
    ASSERT_TRUE(peekTerminalSet(good, info, error)) << error;
    EXPECT_EQ(info.version, kTerminalSetFormatVersion);
    EXPECT_EQ(info.recordCount, 3u);
    EXPECT_EQ(info.shapeCount, 2u);
    EXPECT_EQ(info.header.cell.q, -3);
    EXPECT_EQ(info.header.key, 0x99aabbccddeeff00ull);
    EXPECT_EQ(info.bodyBytes, good.size() - kTerminalSetFixedHeaderBytes - 8);
}

} // namespace
} // namespace hexlod::grammar
