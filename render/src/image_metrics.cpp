// PSNR and SSIM. SSIM's local statistics come from separable Gaussian blurs of x, y, x², y²
// and xy, so a 1280x720 frame costs tens of milliseconds instead of seconds.
#include "hexlod/render/image_metrics.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace hexlod::render {
namespace {

constexpr int kRadius = 5; // 11 taps
constexpr double kSigma = 1.5;

std::vector<double> luma(const Image& image) {
    std::vector<double> y(size_t(image.width) * image.height);
    for (size_t i = 0; i < y.size(); ++i) {
        const float* p = image.pixels.data() + i * image.channels;
        if (image.channels >= 3) {
            y[i] = 0.2126 * std::clamp(p[0], 0.0f, 1.0f) + 0.7152 * std::clamp(p[1], 0.0f, 1.0f) +
                   0.0722 * std::clamp(p[2], 0.0f, 1.0f);
        } else {
            y[i] = std::clamp(p[0], 0.0f, 1.0f);
        }
    }
    return y;
}

// Gaussian blur with edge clamping, normalised per pixel so borders are not darkened.
std::vector<double> blur(const std::vector<double>& in, uint32_t width, uint32_t height) {
    std::array<double, 2 * kRadius + 1> taps;
    for (int i = -kRadius; i <= kRadius; ++i) taps[i + kRadius] = std::exp(-(i * i) / (2 * kSigma * kSigma));
    std::vector<double> rows(in.size()), out(in.size());
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            double sum = 0.0, weight = 0.0;
            for (int i = -kRadius; i <= kRadius; ++i) {
                int64_t sx = int64_t(x) + i;
                if (sx < 0 || sx >= int64_t(width)) continue;
                sum += taps[i + kRadius] * in[size_t(y) * width + size_t(sx)];
                weight += taps[i + kRadius];
            }
            rows[size_t(y) * width + x] = sum / weight;
        }
    }
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            double sum = 0.0, weight = 0.0;
            for (int i = -kRadius; i <= kRadius; ++i) {
                int64_t sy = int64_t(y) + i;
                if (sy < 0 || sy >= int64_t(height)) continue;
                sum += taps[i + kRadius] * rows[size_t(sy) * width + x];
                weight += taps[i + kRadius];
            }
            out[size_t(y) * width + x] = sum / weight;
        }
    }
    return out;
}

bool sameShape(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && a.channels == b.channels && !a.empty();
}

} // namespace

ImageDifference compareImages(const Image& test, const Image& reference, bool coverageAlpha) {
    ImageDifference result;
    if (!sameShape(test, reference)) {
        result.psnr = std::numeric_limits<double>::quiet_NaN();
        return result;
    }
    uint32_t compared = std::min<uint32_t>(test.channels, 3);
    bool masked = coverageAlpha && test.channels == 4;
    double sum = 0.0;
    size_t count = size_t(test.width) * test.height;
    for (size_t i = 0; i < count; ++i) {
        const float* a = test.pixels.data() + i * test.channels;
        const float* b = reference.pixels.data() + i * reference.channels;
        if (masked && a[3] <= 0.0f && b[3] <= 0.0f) continue;
        // Masked images are compared as a viewer sees them over black: colour times coverage.
        const double wa = masked ? std::clamp(a[3], 0.0f, 1.0f) : 1.0,
                     wb = masked ? std::clamp(b[3], 0.0f, 1.0f) : 1.0;
        for (uint32_t c = 0; c < compared; ++c) {
            double d = wa * std::clamp(a[c], 0.0f, 1.0f) - wb * std::clamp(b[c], 0.0f, 1.0f);
            sum += d * d;
            result.maxAbs = std::max(result.maxAbs, std::abs(d));
        }
        ++result.pixels;
    }
    if (result.pixels == 0) {
        result.psnr = std::numeric_limits<double>::infinity();
        return result;
    }
    result.mse = sum / double(result.pixels * compared);
    result.psnr =
        result.mse == 0.0 ? std::numeric_limits<double>::infinity() : -10.0 * std::log10(result.mse);
    return result;
}

double ssim(const Image& test, const Image& reference) {
    if (!sameShape(test, reference)) return std::numeric_limits<double>::quiet_NaN();
    const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    std::vector<double> x = luma(test), y = luma(reference);
    std::vector<double> xx(x.size()), yy(x.size()), xy(x.size());
    for (size_t i = 0; i < x.size(); ++i) {
        xx[i] = x[i] * x[i];
        yy[i] = y[i] * y[i];
        xy[i] = x[i] * y[i];
    }
    uint32_t w = test.width, h = test.height;
    std::vector<double> mx = blur(x, w, h), my = blur(y, w, h);
    std::vector<double> sxx = blur(xx, w, h), syy = blur(yy, w, h), sxy = blur(xy, w, h);
    double total = 0.0;
    for (size_t i = 0; i < x.size(); ++i) {
        double varX = sxx[i] - mx[i] * mx[i], varY = syy[i] - my[i] * my[i], cov = sxy[i] - mx[i] * my[i];
        total += ((2 * mx[i] * my[i] + c1) * (2 * cov + c2)) /
                 ((mx[i] * mx[i] + my[i] * my[i] + c1) * (varX + varY + c2));
    }
    return total / double(x.size());
}

Image boxDownsample(const Image& image, uint32_t factor) {
    if (factor == 0 || image.width < factor || image.height < factor) return Image();
    Image out(image.width / factor, image.height / factor, image.channels);
    const float weight = 1.0f / float(factor * factor);
    for (uint32_t y = 0; y < out.height; ++y)
        for (uint32_t x = 0; x < out.width; ++x) {
            float* to = out.at(x, y);
            for (uint32_t sy = 0; sy < factor; ++sy)
                for (uint32_t sx = 0; sx < factor; ++sx) {
                    const float* from = image.at(x * factor + sx, y * factor + sy);
                    for (uint32_t c = 0; c < image.channels; ++c) to[c] += weight * from[c];
                }
        }
    return out;
}

} // namespace hexlod::render
