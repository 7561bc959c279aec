// The terminal sets' draws after the cull pass: LOD4's instanced meshes, the LOD2 and LOD3
// impostor passes, and what the pass's counters say was drawn.
#include "city_renderer_programs.h"
#include "hexlod/render/gl_api.h"
#include "hexlod/render/gpu_types.h"

#include <algorithm>

namespace hexlod::lod {

void CityRenderer::countCulledTerminals(FrameStats& stats) {
    const uint32_t shapes = cull_.shapeCount();
    if (shapes == 0) return;
    const std::vector<glm::uvec4> counters = cull_.readCounters();
    stats.cullOccludedTerminals += cull_.readOccluded();
    for (uint32_t s = 0; s < shapes; ++s) {
        stats.terminalsPerLod[4] += counters[s].x;
        if (s >= shapes_.firstCoarseShape()) stats.coarseTerminals += counters[s].x;
        stats.terminalsPerLod[3] += counters[s].z;
        stats.terminalsPerLod[2] += counters[s].w;
        // An impostor is one rectangle: two triangles.
        stats.triangles +=
            uint64_t(counters[s].x) * shapes_.triangles(s) + (uint64_t(counters[s].z) + counters[s].w) * 2;
        stats.draws += (counters[s].x > 0) + (counters[s].z > 0) + (counters[s].w > 0);
    }
}

void CityRenderer::drawTerminalMeshes(PassTimer& timer) {
    const uint32_t shapes = cull_.shapeCount();
    if (shapes == 0) return;
    gl::glBindBuffer(GL_DRAW_INDIRECT_BUFFER, cull_.commandBuffer());
    gl::glBindVertexArray(lod4Vao_);
    gl::glVertexArrayVertexBuffer(lod4Vao_, 1, cull_.listBuffer(), 0, sizeof(gpu::GpuTerminal));
    programs_->lod4.use();
    for (const SidedRun& run : shapes_.sidedRuns()) {
        if (run.twoSided) gl::glDisable(GL_CULL_FACE);
        programs_->lod4.set("twoSided", int(run.twoSided));
        gl::glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT,
                                        reinterpret_cast<const void*>(uintptr_t(run.first) * kCommandStride),
                                        GLsizei(run.count), kCommandStride);
        if (run.twoSided) gl::glEnable(GL_CULL_FACE);
    }
    gl::glBindVertexArray(0);
    gl::glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    timer.end(DrawPass::TerminalMeshes);
}

bool CityRenderer::drawImpostors(const glm::mat4& inverseViewProjection, PassTimer& timer) {
    const uint32_t shapes = cull_.shapeCount();
    // Whether the cull wrote impostor entries is known only once it has run; the mode says
    // when it cannot have, and an indirect draw of none costs the GPU nothing.
    if (shapes == 0 || !programs_->impostor.valid() || !impostorsDrawn()) return false;
    // The quads must cover the largest list either pass may draw in one command.
    const DrawListLayout& layout = cull_.layout();
    uint64_t quads = 0;
    for (uint32_t s = 0; s < shapes; ++s)
        quads = std::max<uint64_t>({quads, layout.capacity[s], layout.lod3Capacity[s]});
    if (impostorQuads_.reserve(quads)) gl::glVertexArrayElementBuffer(impostorVao_, impostorQuads_.buffer());
    gl::glBindVertexArray(impostorVao_);
    gl::glBindBuffer(GL_DRAW_INDIRECT_BUFFER, cull_.commandBuffer());
    gl::glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, shapes_.shapeBuffer());
    gl::glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, sphereBuffer_);
    if (options_.samples > 1) gl::glEnable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    // LOD2 on the wall plane first, depth-tested before shading, then the ray-cast LOD3
    // entries, each over draw lists of its own.
    uintptr_t commands = uintptr_t(shapes) * kCommandStride;
    for (const render::ShaderProgram* program : {&programs_->impostorWall, &programs_->impostor}) {
        const bool lod3 = program == &programs_->impostor;
        // LOD3 writes its depth: its entries are tested against everything drawn before it.
        if (lod3) depthTiles_.build(target_.depthTexture(), true);
        gl::glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, lod3 ? cull_.lod3ListBuffer() : cull_.listBuffer());
        program->use();
        impostorTextures_.bind(*program, 0);
        program->set("centralView", centralView_);
        program->set("alphaToCoverage", uint32_t(options_.samples > 1));
        if (lod3) {
            program->set("inverseViewProjection", inverseViewProjection);
            program->set("parallaxIterations", options_.parallaxIterations);
            depthTiles_.bind(*program, kDepthTilesUnit, TileTest::Lod3Impostors, options_.dropHidden);
        }
        gl::glMultiDrawElementsIndirect(GL_TRIANGLES, GL_UNSIGNED_INT,
                                        reinterpret_cast<const void*>(commands), GLsizei(shapes),
                                        kCommandStride);
        commands += uintptr_t(shapes) * kCommandStride;
    }
    gl::glDisable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    gl::glBindVertexArray(0);
    gl::glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    timer.end(DrawPass::Impostors);
    return true;
}

} // namespace hexlod::lod
