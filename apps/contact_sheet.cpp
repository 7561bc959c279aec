#include "contact_sheet.h"

#include <algorithm>

namespace hexlod::apps {

render::Image contactSheet(const impostor::ImpostorAtlas& atlas) {
    const uint32_t size = atlas.layout.atlasSize(), tile = atlas.layout.viewResolution, gap = 8;
    render::Image sheet(2 * size + gap, size, 4, 1.0f);
    for (uint32_t y = 0; y < size; ++y) {
        for (uint32_t x = 0; x < size; ++x) {
            const float* a = atlas.albedo.at(x, y);
            const float* n = atlas.normalDepth.at(x, y);
            const bool gridLine = x % tile == 0 || y % tile == 0;
            const float checker = ((x / 8 + y / 8) % 2) ? 0.55f : 0.45f;
            float* left = sheet.at(x, y);
            float* right = sheet.at(size + gap + x, y);
            for (int c = 0; c < 3; ++c) {
                left[c] = gridLine ? 0.1f : a[c] * a[3] + checker * (1.0f - a[3]);
                // Normals as colours, linearised so the PNG's sRGB encoding shows them as 0.5 + n / 2.
                const float shown = a[3] > 0.0f ? std::clamp(0.5f + 0.5f * n[c], 0.0f, 1.0f) : checker;
                right[c] = gridLine ? 0.1f : shown * shown;
            }
            left[3] = right[3] = 1.0f;
        }
    }
    return sheet;
}

} // namespace hexlod::apps
