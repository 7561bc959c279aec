// The zstd frame helper both payload codecs go through: exact sizes, the errors it names,
// and the per-thread scratch it decodes, lays bodies out and compresses into, which a body
// over kKeptScratchBytes must not leave behind.
#include "zstd_frame.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace hexlod::grammar::detail {
namespace {

std::vector<uint8_t> patterned(size_t bytes) {
    std::vector<uint8_t> body(bytes);
    for (size_t i = 0; i < bytes; ++i) body[i] = uint8_t(i % 251);
    return body;
}

std::vector<uint8_t> frameOf(const std::vector<uint8_t>& body) {
    std::vector<uint8_t> frame;
    compressFrame(body, 1, frame, 0);
    return frame;
}

std::string rejection(const std::vector<uint8_t>& frame, uint64_t expected) {
    std::span<const uint8_t> body;
    std::string error;
    EXPECT_FALSE(decompressFrame(frame, expected, body, error));
    return error;
}

TEST(ZstdFrame, DecodesExactlyTheDeclaredBytesAndNamesEveryMismatch) {
    const std::vector<uint8_t> body = patterned(100000);
    const std::vector<uint8_t> frame = frameOf(body);
    std::span<const uint8_t> decoded;
    std::string error;
    ASSERT_TRUE(decompressFrame(frame, body.size(), decoded, error)) << error;
    EXPECT_TRUE(std::equal(decoded.begin(), decoded.end(), body.begin(), body.end()));

    EXPECT_NE(rejection(frame, body.size() - 1).find("declares 100000 bytes"), std::string::npos);
    EXPECT_NE(rejection({1, 2, 3, 4, 5, 6, 7, 8}, 8).find("not a zstd frame"), std::string::npos);
    std::vector<uint8_t> cut(frame.begin(), frame.end() - 8);
    EXPECT_NE(rejection(cut, body.size()).find("truncated"), std::string::npos);
    std::vector<uint8_t> trailing = frame;
    trailing.push_back(0);
    EXPECT_NE(rejection(trailing, body.size()).find("trailing bytes"), std::string::npos);
}

TEST(ZstdFrame, ABodyOverTheKeptScratchIsReleasedAndASmallOneKept) {
    const std::vector<uint8_t> small = patterned(4096);
    const std::vector<uint8_t> large = patterned(kKeptScratchBytes + (size_t(1) << 20));
    const std::vector<uint8_t> smallFrame = frameOf(small), largeFrame = frameOf(large);
    std::span<const uint8_t> decoded;
    std::string error;
    {
        ScratchRelease release;
        ASSERT_TRUE(decompressFrame(smallFrame, small.size(), decoded, error)) << error;
        EXPECT_TRUE(std::equal(decoded.begin(), decoded.end(), small.begin(), small.end()));
    }
    const size_t kept = threadScratch().decode;
    EXPECT_GE(kept, small.size());
    EXPECT_LE(kept, kKeptScratchBytes);
    {
        ScratchRelease release;
        ASSERT_TRUE(decompressFrame(largeFrame, large.size(), decoded, error)) << error;
        // The view is good until the scope ends: the decoders copy out of it before then.
        EXPECT_GT(threadScratch().decode, kKeptScratchBytes);
        EXPECT_TRUE(std::equal(decoded.begin(), decoded.end(), large.begin(), large.end()));
    }
    EXPECT_EQ(threadScratch().decode, 0u) << "a body over the kept size is not held between payloads";
    {
        ScratchRelease release;
        ASSERT_TRUE(decompressFrame(smallFrame, small.size(), decoded, error)) << error;
        EXPECT_TRUE(std::equal(decoded.begin(), decoded.end(), small.begin(), small.end()));
    }
    EXPECT_GT(threadScratch().decode, 0u);
}

TEST(ZstdFrame, EncodersScratchOverTheKeptSizeIsReleasedAndThePayloadSizedOnce) {
    const std::vector<uint8_t> large = patterned(kKeptScratchBytes + (size_t(1) << 20));
    std::vector<uint8_t> frame(16, 7);
    compressFrame(large, 1, frame, 16);
    EXPECT_EQ(threadScratch().frame, 0u) << "a frame bound over the kept size is not held";
    EXPECT_EQ(frame.capacity(), frame.size());
    EXPECT_EQ(frame[15], 7) << "the bytes before the frame are kept";
    std::span<const uint8_t> decoded;
    std::string error;
    {
        ScratchRelease release;
        ASSERT_TRUE(decompressFrame(std::span(frame).subspan(16), large.size(), decoded, error)) << error;
        EXPECT_TRUE(std::equal(decoded.begin(), decoded.end(), large.begin(), large.end()));
    }
    compressFrame(patterned(4096), 1, frame, 0);
    EXPECT_GT(threadScratch().frame, 0u);
    EXPECT_LE(threadScratch().frame, kKeptScratchBytes);
    {
        ScratchRelease release;
        encoderBody(large.size());
        EXPECT_GE(threadScratch().body, large.size());
    }
    EXPECT_EQ(threadScratch().body, 0u);
    {
        ScratchRelease release;
        encoderBody(4096);
    }
    EXPECT_GE(threadScratch().body, 4096u);
}

} // namespace
} // namespace hexlod::grammar::detail
