// Image files and metrics: PNG and EXR round trips, PSNR on known errors, SSIM's range.
#include "../scratch_folder.h"
#include "hexlod/render/image_io.h"
#include "hexlod/render/image_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include <Imath/half.h>
#include <stb_image.h>

namespace hexlod::render {
namespace {

std::string scratch(const std::string& name) {
    static const testing::ScratchFolder folder("hexlod-image-test");
    return folder.file(name);
}

Image gradient(uint32_t w, uint32_t h) {
    Image image(w, h, 4);
    for (uint32_t y = 0; y < h; ++y) {
        for (uint32_t x = 0; x < w; ++x) {
            float* p = image.at(x, y);
            p[0] = float(x) / float(w - 1);
            p[1] = float(y) / float(h - 1);
            p[2] = 0.5f;
            p[3] = (x + y) % 2 ? 1.0f : 0.25f;
        }
    }
    return image;
}

TEST(ImageIoTest, ExrRoundTripIsExactForHalfValues) {
    Image image = gradient(17, 9);
    for (float& v : image.pixels) v = float(half(v * 3.0f - 1.0f)); // representable, beyond [0, 1]
    std::string path = scratch("round.exr"), error;
    ASSERT_TRUE(writeExr(path, image, error)) << error;
    Image back;
    ASSERT_TRUE(readExr(path, back, error)) << error;
    ASSERT_EQ(back.width, 17u);
    ASSERT_EQ(back.height, 9u);
    ASSERT_EQ(back.channels, 4u);
    EXPECT_EQ(back.pixels, image.pixels);
}

TEST(ImageIoTest, SingleChannelExrKeepsDepth) {
    Image depth(5, 4, 1);
    for (size_t i = 0; i < depth.pixels.size(); ++i) depth.pixels[i] = float(half(float(i) * 0.0625f));
    std::string path = scratch("depth.exr"), error;
    ASSERT_TRUE(writeExr(path, depth, error)) << error;
    Image back;
    ASSERT_TRUE(readExr(path, back, error)) << error;
    EXPECT_EQ(back.channels, 1u);
    EXPECT_EQ(back.pixels, depth.pixels);
}

TEST(ImageIoTest, BadExrFilesAreErrorsNamingThePath) {
    std::string path = scratch("garbage.exr"), error;
    std::ofstream(path) << "not an exr file at all";
    Image back;
    EXPECT_FALSE(readExr(path, back, error));
    EXPECT_EQ(error.rfind(path + ": ", 0), 0u) << error;
    EXPECT_FALSE(readExr(scratch("missing.exr"), back, error));
    // A truncated real file.
    Image image = gradient(32, 32);
    std::string good = scratch("good.exr");
    ASSERT_TRUE(writeExr(good, image, error));
    std::filesystem::resize_file(good, std::filesystem::file_size(good) / 2);
    EXPECT_FALSE(readExr(good, back, error));
    EXPECT_FALSE(writeExr(scratch("empty.exr"), Image(), error));
}

TEST(ImageIoTest, PngIsSrgbEncodedEightBit) {
    Image image = gradient(8, 4);
    std::string path = scratch("gradient.png"), error;
    ASSERT_TRUE(writePng(path, image, error)) << error;
    int w = 0, h = 0, n = 0;
    unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, 4);
    ASSERT_NE(data, nullptr);
    EXPECT_EQ(w, 8);
    EXPECT_EQ(h, 4);
    // Linear 0.5 is sRGB 0.735 (188); alpha is linear.
    EXPECT_EQ(data[2], 188);
    EXPECT_EQ(data[3], 64);
    EXPECT_EQ(data[(3 * 8 + 7) * 4 + 0], 255);
    stbi_image_free(data);
    EXPECT_FALSE(writePng("/nonexistent-dir/x.png", image, error));
}

TEST(ImageMetricsTest, PsnrFollowsTheMeanSquaredError) {
    Image a(10, 10, 4, 0.5f), b(10, 10, 4, 0.5f);
    EXPECT_TRUE(std::isinf(compareImages(a, b).psnr));
    for (size_t i = 0; i < b.pixels.size(); ++i) b.pixels[i] += i % 4 == 3 ? 0.0f : 0.1f;
    ImageDifference d = compareImages(a, b);
    EXPECT_NEAR(d.mse, 0.01, 1e-7); // 0.6f - 0.5f is not exactly 0.1
    EXPECT_NEAR(d.psnr, 20.0, 1e-5);
    EXPECT_NEAR(d.maxAbs, 0.1, 1e-6);
    EXPECT_EQ(d.pixels, 100u);
    EXPECT_TRUE(std::isnan(compareImages(a, Image(10, 9, 4)).psnr));
}

TEST(ImageMetricsTest, CoverageMaskIgnoresEmptyBackground) {
    Image a(10, 10, 4, 0.0f), b(10, 10, 4, 0.0f);
    a.at(3, 3)[3] = 1.0f;
    a.at(3, 3)[0] = 1.0f;
    b.at(3, 3)[3] = 1.0f;
    ImageDifference masked = compareImages(a, b, true);
    EXPECT_EQ(masked.pixels, 1u);
    EXPECT_NEAR(masked.mse, 1.0 / 3.0, 1e-9);
    EXPECT_GT(compareImages(a, b, false).psnr, masked.psnr);
}

TEST(ImageMetricsTest, BoxDownsampleAveragesEachBlock) {
    // A one-pixel checkerboard at 2x is flat grey at 1x: what a supersampled reference shows
    // of detail finer than a pixel.
    Image fine(5, 4, 4);
    for (uint32_t y = 0; y < fine.height; ++y)
        for (uint32_t x = 0; x < fine.width; ++x)
            for (uint32_t c = 0; c < 4; ++c) fine.at(x, y)[c] = float((x + y) % 2);
    const Image coarse = boxDownsample(fine, 2);
    ASSERT_EQ(coarse.width, 2u); // 5 / 2, rounded down
    ASSERT_EQ(coarse.height, 2u);
    for (float v : coarse.pixels) EXPECT_FLOAT_EQ(v, 0.5f);
    EXPECT_EQ(boxDownsample(fine, 1).pixels, fine.pixels);
    EXPECT_TRUE(boxDownsample(fine, 0).empty());
    EXPECT_TRUE(boxDownsample(fine, 6).empty());
}

TEST(ImageMetricsTest, SsimIsOneForIdenticalAndDropsWithNoise) {
    Image a = gradient(64, 48);
    EXPECT_NEAR(ssim(a, a), 1.0, 1e-12);
    Image noisy = a;
    std::mt19937 random(7);
    std::normal_distribution<float> noise(0.0f, 0.1f);
    for (float& v : noisy.pixels) v += noise(random);
    double s = ssim(noisy, a);
    EXPECT_LT(s, 0.9);
    EXPECT_GT(s, 0.0);
    Image tiny = gradient(3, 2);
    EXPECT_NEAR(ssim(tiny, tiny), 1.0, 1e-12);
    EXPECT_TRUE(std::isnan(ssim(a, tiny)));
}

} // namespace
} // namespace hexlod::render
