// Frame constants and draw-list layout for the cull pass.
#include "hexlod/lod/cull_inputs.h"

#include <cmath>

namespace hexlod::lod {

double lodDistance(double geometricError, const scene::LodProfile& profile, double fovY,
                   uint32_t viewportHeight) {
    return geometricError * double(viewportHeight) /
           (2.0 * std::tan(0.5 * fovY) * profile.maxScreenSpaceError);
}

shared::CullFrame makeCullFrame(const cells::Frustum& frustum, const scene::LodProfile& profile, double fovY,
                                uint32_t viewportHeight, double transitionBand, bool impostors) {
    shared::CullFrame frame{};
    const auto& planes = frustum.planes();
    for (size_t i = 0; i < 6; ++i) {
        frame.planes[i] = glm::vec4(glm::vec3(planes[i].normal), float(planes[i].offset));
    }
    const double lod3 = lodDistance(profile.geometricError[3], profile, fovY, viewportHeight);
    const double lod2 = lodDistance(profile.geometricError[2], profile, fovY, viewportHeight);
    frame.lodDistance =
        glm::vec4(float(lod3 * lod3), float(lod2 * lod2), float(transitionBand), impostors ? 1.0f : 0.0f);
    frame.trees = glm::vec4(-1.0f, 0.0f, 0.0f, 0.0f);
    return frame;
}

void setTreeCut(shared::CullFrame& frame, double billboardDistance, const glm::dvec3& treeOrigin,
                const glm::dvec3& camera) {
    const float cut = billboardDistance < 0.0 ? -1.0f : float(billboardDistance * billboardDistance);
    frame.trees = glm::vec4(cut, glm::vec3(treeOrigin - camera));
}

DrawListLayout layoutDrawLists(const CullInputs& inputs) {
    DrawListLayout layout;
    layout.base.assign(inputs.shapeCount, 0);
    layout.capacity.assign(inputs.shapeCount, 0);
    for (const CullBatchInput& batch : inputs.batches) {
        for (size_t s = 0; s < batch.set->countPerShape.size(); ++s) {
            layout.capacity[batch.shapeBase + s] += batch.set->countPerShape[s];
        }
    }
    for (uint32_t s = 0; s < inputs.shapeCount; ++s) {
        layout.base[s] = uint32_t(layout.total);
        layout.total += layout.capacity[s];
    }
    return layout;
}

} // namespace hexlod::lod
