// CPU reconstruction of impostor views with parallax correction.
#include "hexlod/impostor/impostor_reconstruction.h"

#include <algorithm>
#include <cmath>

namespace hexlod::impostor {

glm::vec4 sampleView(const render::Image& image, const ViewLayout& layout, uint32_t view, glm::vec2 uv) {
    const glm::uvec2 origin = layout.tileOrigin(view);
    const float inner = float(layout.innerResolution());
    // Texel centres of the inner area span [padding + 0.5, padding + inner - 0.5].
    float x = float(layout.padding) + (uv.x * 0.5f + 0.5f) * inner - 0.5f;
    float y = float(layout.padding) + (0.5f - uv.y * 0.5f) * inner - 0.5f;
    const float lo = float(layout.padding), hi = float(layout.padding) + inner - 1.0f;
    x = std::clamp(x, lo, hi);
    y = std::clamp(y, lo, hi);
    const uint32_t x0 = uint32_t(x), y0 = uint32_t(y);
    const uint32_t x1 = std::min(x0 + 1, uint32_t(hi)), y1 = std::min(y0 + 1, uint32_t(hi));
    const float fx = x - float(x0), fy = y - float(y0);
    auto texel = [&](uint32_t tx, uint32_t ty) {
        const float* p = image.at(origin.x + tx, origin.y + ty);
        return glm::vec4(p[0], p[1], p[2], p[3]);
    };
    return glm::mix(glm::mix(texel(x0, y0), texel(x1, y0), fx), glm::mix(texel(x0, y1), texel(x1, y1), fx),
                    fy);
}

bool reconstructView(const ImpostorAtlas& atlas, const ViewLookup& lookup, const glm::vec3& direction,
                     uint32_t resolution, const ReconstructionOptions& options, Reconstruction& out) {
    ViewWeights weights;
    if (!lookup.nearestViews(direction, weights)) return false;
    return reconstructView(atlas, weights, direction, resolution, options, out);
}

bool reconstructView(const ImpostorAtlas& atlas, ViewWeights weights, const glm::vec3& direction,
                     uint32_t resolution, const ReconstructionOptions& options, Reconstruction& out) {
    if (resolution == 0 || weights.count == 0 || !(glm::length(direction) > 0.0f)) return false;
    if (options.centralViewOnly) {
        weights.weights = {1.0f, 0.0f, 0.0f, 0.0f};
        weights.count = 1;
    }
    const ViewLayout& layout = atlas.layout;
    const glm::vec3 forward = glm::normalize(direction);
    const ViewBasis target = viewBasis(layout.sphere, forward);
    ViewBasis sources[4];
    for (uint32_t i = 0; i < weights.count; ++i)
        sources[i] = viewBasis(layout.sphere, layout.direction(weights.views[i]));

    out.albedo = render::Image(resolution, resolution, 4);
    out.normalDepth = render::Image(resolution, resolution, 4);
    for (uint32_t py = 0; py < resolution; ++py) {
        for (uint32_t px = 0; px < resolution; ++px) {
            // The pixel's ray, in units of the radius about the centre: origin on the target's
            // centre plane, running along `forward`.
            glm::vec2 p((float(px) + 0.5f) / float(resolution) * 2.0f - 1.0f,
                        1.0f - (float(py) + 0.5f) / float(resolution) * 2.0f);
            glm::vec3 rayOrigin = p.x * target.right + p.y * target.up;
            glm::vec4 colour(0.0f), normalDepth(0.0f);
            float coverage = 0.0f, depthWeight = 0.0f;
            for (uint32_t i = 0; i < weights.count; ++i) {
                if (weights.weights[i] <= 0.0f) continue;
                const ViewBasis& view = sources[i];
                float s = 0.0f; // position along the ray
                glm::vec2 uv;
                for (uint32_t iteration = 0;; ++iteration) {
                    glm::vec3 q = rayOrigin + s * forward;
                    uv = glm::vec2(glm::dot(q, view.right), glm::dot(q, view.up));
                    if (iteration == options.parallaxIterations) break;
                    // The surface this view stores there, and the point of the ray nearest to it.
                    float depth = sampleView(atlas.normalDepth, layout, weights.views[i], uv).w;
                    glm::vec3 surface = uv.x * view.right + uv.y * view.up + depth * view.forward;
                    s = glm::dot(surface - rayOrigin, forward);
                }
                glm::vec4 a = sampleView(atlas.albedo, layout, weights.views[i], uv);
                glm::vec4 n = sampleView(atlas.normalDepth, layout, weights.views[i], uv);
                float w = weights.weights[i] * a.a;
                colour += w * glm::vec4(glm::vec3(a), 1.0f);
                normalDepth += w * glm::vec4(glm::vec3(n), 0.0f);
                depthWeight += w;
                // Depth toward the target viewer of the surface this view sees.
                glm::vec3 surface = uv.x * view.right + uv.y * view.up + n.w * view.forward;
                normalDepth.w += w * glm::dot(surface, forward);
                coverage += w;
            }
            float* outAlbedo = out.albedo.at(px, py);
            float* outNormal = out.normalDepth.at(px, py);
            if (coverage > 0.0f) {
                glm::vec3 c = glm::vec3(colour) / colour.w, n = glm::vec3(normalDepth);
                n = glm::length(n) > 0.0f ? glm::normalize(n) : glm::vec3(0.0f);
                outAlbedo[0] = c.r;
                outAlbedo[1] = c.g;
                outAlbedo[2] = c.b;
                outNormal[0] = n.x;
                outNormal[1] = n.y;
                outNormal[2] = n.z;
                outNormal[3] = normalDepth.w / depthWeight;
            } else {
                outNormal[3] = -1.0f;
            }
            outAlbedo[3] = std::min(coverage, 1.0f);
        }
    }
    return true;
}

} // namespace hexlod::impostor
