// A float image in memory: what framebuffer readback gives and what image files and metrics
// take. Rows run top to bottom (GL's bottom-up rows are flipped on readback).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace hexlod::render {

struct Image {
    uint32_t width = 0, height = 0;
    uint32_t channels = 4;     // 4: RGBA (colour, normal); 1: depth
    std::vector<float> pixels; // width * height * channels, row-major

    Image() = default;
    Image(uint32_t w, uint32_t h, uint32_t c, float fill = 0.0f)
        : width(w), height(h), channels(c), pixels(size_t(w) * h * c, fill) {}
    float* at(uint32_t x, uint32_t y) { return pixels.data() + (size_t(y) * width + x) * channels; }
    const float* at(uint32_t x, uint32_t y) const {
        return pixels.data() + (size_t(y) * width + x) * channels;
    }
    bool empty() const { return pixels.empty(); }
};

} // namespace hexlod::render
