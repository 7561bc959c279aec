// Alpha-weighted means over each view's inner square (its padding is empty by construction).
#include "hexlod/lod/tree_view_averages.h"

namespace hexlod::lod {

std::vector<glm::vec4> treeViewAverages(const impostor::ImpostorAtlas& atlas) {
    const impostor::ViewLayout& layout = atlas.layout;
    std::vector<glm::vec4> out;
    out.reserve(2 * layout.viewCount());
    const uint32_t inner = layout.innerResolution();
    for (uint32_t view = 0; view < layout.viewCount(); ++view) {
        const glm::uvec2 tile = layout.tileOrigin(view) + glm::uvec2(layout.padding);
        glm::dvec3 albedo(0.0), normal(0.0);
        double alpha = 0.0;
        for (uint32_t y = 0; y < inner; ++y)
            for (uint32_t x = 0; x < inner; ++x) {
                const float* a = atlas.albedo.at(tile.x + x, tile.y + y);
                const float* n = atlas.normalDepth.at(tile.x + x, tile.y + y);
                albedo += double(a[3]) * glm::dvec3(a[0], a[1], a[2]);
                normal += double(a[3]) * glm::dvec3(n[0], n[1], n[2]);
                alpha += a[3];
            }
        const double texels = double(inner) * inner;
        out.emplace_back(alpha > 0.0 ? glm::vec3(albedo / alpha) : glm::vec3(0.0f), float(alpha / texels));
        out.emplace_back(alpha > 0.0 ? glm::vec3(normal / alpha) : glm::vec3(0.0f), 0.0f);
    }
    return out;
}

} // namespace hexlod::lod
