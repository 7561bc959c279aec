// PNG encoding: what a decoder reads back is the samples given, for RGBA and grey, sizes down to
// one pixel; content whose rows take several different filters; mismatched sizes refused.
#include "hexlod/render/png_encoder.h"

#include <gtest/gtest.h>
#include <stb_image.h>
#include <zlib.h>

#include <cstdint>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace hexlod::render {
namespace {

// Flat runs, horizontal and vertical ramps, a smooth field and noise, band by band.
std::vector<uint8_t> samples(uint32_t width, uint32_t height, uint32_t channels, uint32_t seed) {
    std::mt19937 random(seed);
    std::vector<uint8_t> out(size_t(width) * height * channels);
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            for (uint32_t c = 0; c < channels; ++c) {
                uint8_t& v = out[(size_t(y) * width + x) * channels + c];
                switch (y % 5) {
                case 0:
                    v = uint8_t(40 * c);
                    break;
                case 1:
                    v = uint8_t(3 * x + c);
                    break;
                case 2:
                    v = uint8_t(5 * y + 7 * c);
                    break;
                case 3:
                    v = uint8_t(x * y / 3 + c);
                    break;
                default:
                    v = uint8_t(random());
                }
            }
        }
    }
    return out;
}

std::vector<uint8_t> decode(const std::vector<uint8_t>& png, uint32_t channels, int& width, int& height) {
    int stored = 0;
    unsigned char* data =
        stbi_load_from_memory(png.data(), int(png.size()), &width, &height, &stored, int(channels));
    if (!data) return {};
    std::vector<uint8_t> out(data, data + size_t(width) * height * channels);
    stbi_image_free(data);
    return out;
}

TEST(PngEncoderTest, ADecoderReadsBackTheSamples) {
    const uint32_t sizes[][2] = {{1, 1}, {1, 7}, {9, 1}, {64, 40}, {513, 257}};
    for (const uint32_t channels : {4u, 1u}) {
        for (const auto& [w, h] : sizes) {
            const std::vector<uint8_t> given = samples(w, h, channels, w * 31 + h);
            const std::vector<uint8_t> png = encodePngSamples(given, w, h, channels);
            ASSERT_FALSE(png.empty());
            int width = 0, height = 0;
            EXPECT_EQ(decode(png, channels, width, height), given) << w << "x" << h << "x" << channels;
            EXPECT_EQ(width, int(w));
            EXPECT_EQ(height, int(h));
        }
    }
}

TEST(PngEncoderTest, EachRowTakesTheFilterThatFitsIt) {
    const uint32_t width = 256, height = 200, stride = width * 4;
    const std::vector<uint8_t> given = samples(width, height, 4, 7);
    const std::vector<uint8_t> png = encodePngSamples(given, width, height, 4);
    ASSERT_FALSE(png.empty());
    EXPECT_LT(png.size(), given.size() / 3);
    // The one IDAT chunk after the signature and IHDR (8 + 25 bytes), inflated: a filter type
    // byte before each row.
    const auto be32 = [&](size_t at) {
        return uint32_t(png[at]) << 24 | uint32_t(png[at + 1]) << 16 | uint32_t(png[at + 2]) << 8 |
               png[at + 3];
    };
    ASSERT_EQ(std::string(png.begin() + 37, png.begin() + 41), "IDAT");
    std::vector<uint8_t> raw(size_t(stride + 1) * height);
    uLongf rawSize = uLongf(raw.size());
    ASSERT_EQ(uncompress(raw.data(), &rawSize, png.data() + 41, be32(33)), Z_OK);
    ASSERT_EQ(rawSize, raw.size());
    std::set<int> chosen;
    for (uint32_t y = 0; y < height; ++y) {
        const int type = raw[size_t(y) * (stride + 1)];
        ASSERT_LE(type, 4);
        chosen.insert(type);
    }
    EXPECT_GE(chosen.size(), 3u) << "flat runs, ramps and noise do not all fit one filter";
}

TEST(PngEncoderTest, SizesThatDoNotMatchTheSamplesAreRefused) {
    const std::vector<uint8_t> given(12, 0);
    EXPECT_TRUE(encodePngSamples(given, 2, 2, 3).empty()) << "three channels are not written";
    EXPECT_TRUE(encodePngSamples(given, 2, 2, 4).empty()) << "16 samples asked, 12 given";
    EXPECT_TRUE(encodePngSamples(given, 0, 3, 4).empty());
    EXPECT_TRUE(encodePngSamples({}, 0, 0, 1).empty());
    EXPECT_FALSE(encodePngSamples(given, 3, 4, 1).empty());
}

} // namespace
} // namespace hexlod::render
