// The extruded-set codec: byte-exact round trips on a real batch, golden bytes that pin
// format version 1, and rejection of every truncation, harmful bit flip and lying header.
#include "hexlod/grammar/batch_expander.h"
#include "hexlod/grammar/extruded_set_codec.h"
#include "hexlod/scene/demo_footprints.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>

namespace hexlod::grammar {
namespace {

bool sameSet(const ExtrudedSet& a, const ExtrudedSet& b) {
    if (a.buildings.size() != b.buildings.size() || a.footprints != b.footprints ||
        a.elements.size() != b.elements.size() || a.parameters.size() != b.parameters.size())
        return false;
    for (size_t i = 0; i < a.buildings.size(); ++i) {
        const ExtrudedBuilding &x = a.buildings[i], &y = b.buildings[i];
        if (x.building != y.building || x.firstVertex != y.firstVertex || x.vertexCount != y.vertexCount ||
            x.firstElement != y.firstElement || x.elementCount != y.elementCount ||
            x.firstParameter != y.firstParameter || std::memcmp(&x.baseElevation, &y.baseElevation, 4) != 0 ||
            std::memcmp(&x.height, &y.height, 4) != 0 || x.wallMaterial != y.wallMaterial)
            return false;
    }
    for (size_t i = 0; i < a.elements.size(); ++i) {
        const ExtrudedElement &x = a.elements[i], &y = b.elements[i];
        if (std::memcmp(&x.origin, &y.origin, 12) || std::memcmp(&x.axisX, &y.axisX, 12) ||
            std::memcmp(&x.axisY, &y.axisY, 12) || std::memcmp(&x.size, &y.size, 8) || x.rule != y.rule ||
            x.atom != y.atom)
            return false;
    }
    return a.parameters.empty() ||
           std::memcmp(a.parameters.data(), b.parameters.data(), 4 * a.parameters.size()) == 0;
}

bool sameHeader(const ExtrudedSetHeader& a, const ExtrudedSetHeader& b) {
    return a.cell.q == b.cell.q && a.cell.r == b.cell.r && a.grammar == b.grammar &&
           a.grammarHash == b.grammarHash && a.key == b.key &&
           std::memcmp(a.cellOrigin, b.cellOrigin, sizeof(a.cellOrigin)) == 0;
}

ExtrudedSet residentialExtruded(uint32_t buildings) {
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
    return expandBatch(batch).extruded;
}

ExtrudedSetHeader goldenHeader() {
    ExtrudedSetHeader h;
    h.cell = {-3, 5};
    h.grammar = 2;
    h.grammarHash = 0x1122334455667788ull;
    h.key = 0x99aabbccddeeff00ull;
    h.cellOrigin[0] = 1000.5;
    h.cellOrigin[1] = -250.25;
    h.cellOrigin[2] = 12.0;
    return h;
}

// Two buildings: a triangle with one facade element and a square with two, two parameters each.
// Changing the layout must change the golden bytes below: then bump kExtrudedSetFormatVersion
// and regenerate them.
ExtrudedSet goldenSet() {
    ExtrudedSet s;
    s.footprints = {{0, 0}, {4, 0}, {0, 3}, {10, 10}, {12, 10}, {12, 12}, {10, 12}};
    s.elements = {
        {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {4, 9}, 7, 0},
        {{10, 10, 0}, {1, 0, 0}, {0, 0, 1}, {2, 6}, 7, 0},
        {{12, 10, 0}, {0, 1, 0}, {0, 0, 1}, {2, 6}, 7, 1},
    };
    s.parameters = {3.0f, 2.5f, 3.2f, 2.5f};
    s.buildings = {{10, 0, 3, 0, 1, 0, 0.0f, 9.0f, 2}, {11, 3, 4, 1, 2, 2, 0.5f, 6.0f, 0}};
    return s;
}

const std::vector<uint8_t> kGolden = {
    // clang-format off
    // magic, version
    0x48, 0x58, 0x45, 0x31, 0x01, 0x00, 0x00, 0x00,
    // checksum
    0x8c, 0x6c, 0x22, 0xa9, 0xea, 0xdc, 0xd1, 0x1c,
    // cell q, r; grammar; parameters per building
    0xfd, 0xff, 0xff, 0xff, 0x05, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00,
    0x02, 0x00, 0x00, 0x00,
    // grammar hash; key
    0x88, 0x77, 0x66, 0x55, 0x44, 0x33, 0x22, 0x11, 0x00, 0xff, 0xee, 0xdd,
    0xcc, 0xbb, 0xaa, 0x99,
    // cell origin
    0x00, 0x00, 0x00, 0x00, 0x00, 0x44, 0x8f, 0x40, 0x00, 0x00, 0x00, 0x00,
    0x00, 0x48, 0x6f, 0xc0, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x28, 0x40,
    // buildings, vertices, elements, reserved
    0x02, 0x00, 0x00, 0x00, 0x07, 0x00, 0x00, 0x00, 0x03, 0x00, 0x00, 0x00,
    0x00, 0x00, 0x00, 0x00,
    // body bytes
    0x7f, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    // zstd frame
    0x28, 0xb5, 0x2f, 0xfd, 0x60, 0x14, 0x00, 0xad, 0x03, 0x00, 0x72, 0x04,
    0x0e, 0x1b, 0xb0, 0x25, 0x69, 0x0c, 0x0c, 0x83, 0x17, 0x2e, 0x6b, 0x18,
    0x8a, 0x6c, 0x3d, 0x49, 0x8e, 0x82, 0x62, 0x75, 0x0a, 0x47, 0x02, 0x65,
    0xc1, 0xad, 0x91, 0x96, 0x02, 0x2b, 0xaf, 0xbc, 0x81, 0xe1, 0xb0, 0xfd,
    0x61, 0xe8, 0x99, 0xa8, 0xa9, 0xba, 0x0b, 0x9b, 0xaa, 0x8a, 0x40, 0x76,
    0x16, 0x00, 0x36, 0xc4, 0x8d, 0x17, 0x27, 0x0f, 0x04, 0x1a, 0x00, 0x28,
    0x33, 0x00, 0xe4, 0x0b, 0x88, 0x20, 0xc0, 0xd0, 0x0c, 0xd8, 0x13, 0xf0,
    0x60, 0xb0, 0xd2, 0xe0, 0xab, 0x17, 0x00, 0x08, 0x33, 0x11, 0xc8, 0x71,
    0xb0, 0x1b, 0xb8, 0x42, 0x02, 0x10, 0xf8, 0x6a, 0xc0, 0x54, 0x1b, 0x70,
    0x03, 0x86, 0xd2, 0x75, 0x42, 0xd0, 0x60, 0x09, 0x60, 0x0f, 0x5a, 0xb0,
    0xa9, 0x11, 0x64, 0x70, 0xb2, 0xb9, 0x04
    // clang-format on
};

TEST(ExtrudedSetCodec, RoundTripsARealBatchByteExactly) {
    const ExtrudedSet set = residentialExtruded(60);
    ASSERT_EQ(set.buildings.size(), 60u);
    ASSERT_GT(set.elements.size(), 100u);
    ExtrudedSetHeader header = goldenHeader();
    const std::vector<uint8_t> encoded = encodeExtrudedSet(header, set);
    ExtrudedSetHeader decodedHeader;
    ExtrudedSet decoded;
    std::string error;
    ASSERT_TRUE(decodeExtrudedSet(encoded, decodedHeader, decoded, error)) << error;
    EXPECT_TRUE(sameSet(set, decoded));
    EXPECT_TRUE(sameHeader(header, decodedHeader));
    std::printf(
        "[ residential ] %zu buildings, %zu elements: %zu bytes in memory, %zu encoded (%.1f B/building)\n",
        set.buildings.size(), set.elements.size(), set.byteSize(), encoded.size(),
        double(encoded.size()) / double(set.buildings.size()));
    EXPECT_LT(encoded.size(), set.byteSize());
}

TEST(ExtrudedSetCodec, RoundTripsAnEmptySet) {
    const std::vector<uint8_t> encoded = encodeExtrudedSet(goldenHeader(), {});
    ExtrudedSetHeader header;
    ExtrudedSet decoded;
    std::string error;
    ASSERT_TRUE(decodeExtrudedSet(encoded, header, decoded, error)) << error;
    EXPECT_TRUE(decoded.buildings.empty());
    EXPECT_TRUE(sameHeader(header, goldenHeader()));
}

TEST(ExtrudedSetCodec, EncodingMatchesTheGoldenBytes) {
    const std::vector<uint8_t> encoded = encodeExtrudedSet(goldenHeader(), goldenSet());
    std::string hex;
    for (uint8_t byte : encoded) {
        char text[8];
        std::snprintf(text, sizeof(text), "0x%02x, ", byte);
        hex += text;
    }
    EXPECT_EQ(encoded, kGolden) << "encoded: " << hex;
}

TEST(ExtrudedSetCodec, GoldenBytesDecodeToTheHandBuiltSet) {
    ExtrudedSetHeader header;
    ExtrudedSet decoded;
    std::string error;
    ASSERT_TRUE(decodeExtrudedSet(kGolden, header, decoded, error)) << error;
    EXPECT_TRUE(sameSet(goldenSet(), decoded));
    EXPECT_TRUE(sameHeader(goldenHeader(), header));
}

TEST(ExtrudedSetCodec, RejectsEveryTruncationAndEveryHarmfulBitFlip) {
    const std::vector<uint8_t> good = encodeExtrudedSet(goldenHeader(), goldenSet());
    ExtrudedSetHeader header;
    ExtrudedSet decoded;
    std::string error;
    for (size_t length = 0; length < good.size(); ++length) {
        error.clear();
        EXPECT_FALSE(decodeExtrudedSet(std::span(good.data(), length), header, decoded, error)) << length;
        EXPECT_FALSE(error.empty());
    }
    size_t harmless = 0;
    for (size_t bit = 0; bit < good.size() * 8; ++bit) {
        std::vector<uint8_t> flipped = good;
        flipped[bit / 8] ^= uint8_t(1u << (bit % 8));
        error.clear();
        if (decodeExtrudedSet(flipped, header, decoded, error)) {
            EXPECT_TRUE(sameSet(goldenSet(), decoded)) << "bit " << bit;
            EXPECT_TRUE(sameHeader(goldenHeader(), header)) << "bit " << bit;
            ++harmless;
        } else {
            EXPECT_FALSE(error.empty());
        }
    }
    EXPECT_LT(harmless, good.size());
    std::vector<uint8_t> longer = good;
    longer.push_back(0);
    EXPECT_FALSE(decodeExtrudedSet(longer, header, decoded, error));
    EXPECT_NE(error.find("trailing"), std::string::npos) << error;
}

template <typename T> std::vector<uint8_t> with(std::vector<uint8_t> payload, size_t offset, T value) {
    std::memcpy(payload.data() + offset, &value, sizeof(T));
    return payload;
}

void expectRejected(const std::vector<uint8_t>& payload, const std::string& reason) {
    ExtrudedSetHeader header;
    ExtrudedSet decoded;
    std::string error;
    EXPECT_FALSE(decodeExtrudedSet(payload, header, decoded, error));
    EXPECT_NE(error.find(reason), std::string::npos) << error;
}

TEST(ExtrudedSetCodec, RejectsForeignInputAndLyingHeadersWithAReason) {
    const std::vector<uint8_t> good = encodeExtrudedSet(goldenHeader(), goldenSet());
    expectRejected(with<char>(good, 0, 'T'), "bad magic");
    expectRejected(with<uint32_t>(good, 4, 2), "unsupported extruded-set version 2");
    expectRejected(with<uint32_t>(good, 72, kExtrudedSetMaxBuildings + 1), "limits");
    expectRejected(with<uint32_t>(good, 28, kExtrudedSetMaxParameters + 1), "limits");
    expectRejected(with<uint32_t>(good, 84, 1), "reserved");
    expectRejected(with<uint64_t>(good, 88, 1), "trailing bytes");
    expectRejected(with<uint64_t>(good, 88, 1u << 20), "truncated");
    expectRejected(with<uint32_t>(good, 76, 8),
                   "bytes, the header needs"); // one vertex more than the body holds
    expectRejected(std::vector<uint8_t>(200, 0), "bad magic");
    // A body that decodes fine under another set's checksum: the checksum covers the decoded
    // columns (here a vertex moved from building 1 to building 0), not just the frame.
    ExtrudedSet moved = goldenSet();
    moved.buildings[0].vertexCount = 4;
    moved.buildings[1].firstVertex = 4;
    moved.buildings[1].vertexCount = 3;
    const std::vector<uint8_t> other = encodeExtrudedSet(goldenHeader(), moved);
    std::vector<uint8_t> forged = good;
    std::memcpy(forged.data() + 8, other.data() + 8, 8); // the other set's checksum on this body
    expectRejected(forged, "checksum mismatch");
}

TEST(ExtrudedSetCodec, ALyingBuildingCountCostsNoHugeAllocation) {
    const std::vector<uint8_t> payload =
        with<uint32_t>(encodeExtrudedSet(goldenHeader(), {}), 72, kExtrudedSetMaxBuildings);
    expectRejected(with<uint32_t>(payload, 28, kExtrudedSetMaxParameters), "bytes, the header needs");
}

TEST(ExtrudedSetCodec, RefusesToEncodeANonContiguousSet) {
    ExtrudedSet set = goldenSet();
    set.buildings[1].firstVertex = 0;
    EXPECT_THROW(encodeExtrudedSet(goldenHeader(), set), std::invalid_argument);
    set = goldenSet();
    set.parameters.pop_back();
    EXPECT_THROW(encodeExtrudedSet(goldenHeader(), set), std::invalid_argument);
}

} // namespace
} // namespace hexlod::grammar
