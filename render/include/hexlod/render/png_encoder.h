// PNG encoding of 8-bit samples with zlib. stb_image_write, used before, chose row filters the
// same way but deflated with its own compressor: a 1280x720 walk frame took 154 ms against
// 91 ms here, a 512 x 512 atlas 34 against 16 ms, for files 7 to 15 % smaller
// (docs/BENCHMARKS.md, "PNG through zlib").
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace hexlod::render {

// The PNG file of `width` x `height` pixels of `channels` (4: RGBA, 1: grey) 8-bit samples,
// rows top to bottom; each row takes the filter whose output is smallest in absolute sum (as
// libpng chooses). Empty when the sizes do not match the samples or zlib fails.
std::vector<uint8_t> encodePngSamples(std::span<const uint8_t> samples, uint32_t width, uint32_t height,
                                      uint32_t channels);

} // namespace hexlod::render
