// The reference pass: a loop over the records with the shared decision.
#include "hexlod/lod/cpu_cull.h"
#include "hexlod/lod/occlusion_tests.h"

#include <cstring>

namespace hexlod::lod {

CullResult cullOnCpu(const CullInputs& inputs) {
    CullResult result;
    result.lod4.resize(inputs.shapeCount);
    result.impostor.resize(inputs.shapeCount);
    // The coarse meshes as the GPU pass sees them, with the draw lists it would lay out.
    const std::vector<glm::vec4> coarse =
        inputs.shapeCoarse.empty() ? inputs.shapeCoarse : coarseTable(inputs, selectCullPages(inputs).layout);
    for (const CullBatchInput& batch : inputs.batches) {
        // The GPU receives the origin as float, rounded from the double difference.
        const glm::vec3 origin = glm::vec3(batch.cellOrigin - inputs.camera);
        for (const grammar::TerminalRecord& record : batch.set->records) {
            gpu::GpuTerminal t;
            std::memcpy(&t, &record, sizeof t);
            const uint32_t shape = batch.shapeBase + (t.shapeAndDepth & 0xffffu);
            const bool treePart = !inputs.shapeTree.empty() && inputs.shapeTree[shape];
            if (treePart && shared::treeIsBillboard(glm::vec3((*inputs.trees)[t.building]), inputs.frame)) {
                ++result.culled;
                continue;
            }
            const glm::vec3 corner = t.position + origin;
            float transition = 0.0f;
            glm::vec4 sphere;
            const uint32_t lod = shared::classifyTerminal(
                t, corner, inputs.frame, inputs.shapeImpostor[shape] != 0, !treePart, transition, sphere);
            if (lod == HEXLOD_CULLED) {
                ++result.culled;
                continue;
            }
            if (tilesHideSphere(inputs.frame, inputs.occlusionTiles, sphere, HEXLOD_OCCLUSION_MAX_TILES)) {
                ++result.culled;
                ++result.occluded;
                continue;
            }
            const uint32_t drawn = lod == HEXLOD_LOD4 && !coarse.empty()
                                       ? shared::meshShape(t, shape, coarse[shape], sphere, inputs.frame)
                                       : shape;
            t.position = corner;
            t.building = std::bit_cast<uint32_t>(lod == HEXLOD_LOD2 ? -1.0f : transition);
            t.shapeAndDepth = (t.shapeAndDepth & 0xffff0000u) | drawn;
            ++result.terminalsPerLod[lod];
            (lod == HEXLOD_LOD4 ? result.lod4 : result.impostor)[drawn].push_back({t, lod});
        }
    }
    return result;
}

} // namespace hexlod::lod
