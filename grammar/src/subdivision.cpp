#include "hexlod/grammar/subdivision.h"

#include <cmath>

namespace hexlod::grammar {

SubdivisionStatus splitSizes(float length, const float* sizes, const bool* relative, uint32_t count,
                             float* parts) {
    SubdivisionStatus status = SubdivisionStatus::Ok;
    double absoluteSum = 0.0, relativeSum = 0.0;
    for (uint32_t i = 0; i < count; ++i) {
        float size = sizes[i];
        if (!std::isfinite(size) || size < 0.0f) {
            status = SubdivisionStatus::InvalidSize;
            size = 0.0f;
        }
        parts[i] = size;
        (relative[i] ? relativeSum : absoluteSum) += size;
    }
    const double available = std::fmax(0.0, static_cast<double>(length));
    const double remainder = available - absoluteSum;
    const double absoluteScale = remainder < 0.0 ? available / absoluteSum : 1.0;
    const double relativeScale = (remainder > 0.0 && relativeSum > 0.0) ? remainder / relativeSum : 0.0;
    for (uint32_t i = 0; i < count; ++i) {
        parts[i] = static_cast<float>(parts[i] * (relative[i] ? relativeScale : absoluteScale));
    }
    return status;
}

SubdivisionStatus repeatLayout(float length, float size, RepeatMode mode, uint32_t maxTiles,
                               RepeatLayout& layout) {
    layout = RepeatLayout{};
    if (!std::isfinite(size) || !(size > 0.0f)) return SubdivisionStatus::InvalidSize;
    if (!(length > 0.0f)) return SubdivisionStatus::Ok;
    // Counting in double keeps a size that tends to 0 from overflowing the tile count.
    const double ratio = static_cast<double>(length) / static_cast<double>(size);
    // The 1e-5 slack keeps float round-off (a 2.9999998 m facade for 3 m tiles) from
    // losing a tile in fit mode.
    const double tiles =
        mode == RepeatMode::Fit ? std::floor(ratio + 1e-5) : std::fmax(1.0, std::nearbyint(ratio));
    if (tiles > static_cast<double>(maxTiles)) return SubdivisionStatus::TooManyTiles;
    layout.tiles = static_cast<uint32_t>(tiles);
    if (mode == RepeatMode::Fit) {
        layout.tileSize = size;
        layout.margin = static_cast<float>(std::fmax(0.0, 0.5 * (length - tiles * size)));
    } else {
        layout.tileSize = static_cast<float>(length / tiles);
    }
    return SubdivisionStatus::Ok;
}

} // namespace hexlod::grammar
