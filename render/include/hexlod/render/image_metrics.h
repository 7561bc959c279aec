// Image error metrics for the error-against-run-time reports (ARCHITECTURE.md §8): PSNR and
// SSIM of a test image against a reference of the same size, on RGB in [0, 1].
#pragma once

#include "hexlod/render/image.h"

#include <limits>

namespace hexlod::render {

struct ImageDifference {
    double mse = 0.0;  // mean squared error over the compared pixels and RGB channels
    double psnr = 0.0; // dB, peak 1; +infinity for identical images
    double maxAbs = 0.0;
    uint64_t pixels = 0; // compared pixels
};

// Compares RGB (the first three channels; a single channel image compares that one). With
// `coverageAlpha`, colours are weighted by their alpha (the images as seen over black) and
// only pixels where either image's alpha exceeds 0 count, so a shape's error is not diluted
// by empty background. Images of different sizes or channel counts
// give pixels == 0 and psnr == NaN.
ImageDifference compareImages(const Image& test, const Image& reference, bool coverageAlpha = false);

// Structural similarity (Wang et al. 2004) on Rec. 709 luma, with an 11x11 Gaussian window of
// sigma 1.5 and the paper's constants; the mean over the image, in [-1, 1], 1 for identical
// images. NaN for mismatched sizes; images smaller than the window use the whole image.
double ssim(const Image& test, const Image& reference);

// The mean of each factor x factor block: a supersampled render filtered down to its display
// size, the ground truth an image error should be measured against (a one-sample reference
// scores the sub-pixel detail it aliases as error). The size is rounded down; an empty image
// for factor 0 or an image smaller than one block.
Image boxDownsample(const Image& image, uint32_t factor);

} // namespace hexlod::render
