// The frame's base volumes (LOD0, LOD1 and the shells under terminal sets), ring by ring.
#include "city_renderer_programs.h"
#include "hexlod/lod/building_order.h"
#include "hexlod/lod/cull_inputs.h"
#include "hexlod/lod/occlusion_tests.h"
#include "hexlod/lod/wall_texture_mean.h"
#include "hexlod/render/gl_api.h"

namespace hexlod::lod {
namespace {

// building_point.vert's BuildingPointBuffer.
constexpr uint32_t kBuildingPointBinding = 17;

} // namespace

void CityRenderer::drawVolumeRings(const std::vector<VolumeDraw>& volumes, const scene::CameraPose& pose,
                                   double nearPlane, double farPlane, FrameStats& stats, PassTimer& timer) {
    shared::CullFrame occlusion{};
    setOcclusion(occlusion, pose.forward, pose.up, pose.fovY, nearPlane, farPlane, options_.width,
                 options_.height, volumeTiles_.columns(), volumeTiles_.rows(), volumeTiles_.tileSize());
    const bool test = options_.dropHidden && volumeTiles_.valid();
    const float pixelsPerMetre = float(screenScale(pose.fovY, options_.height));
    const BuildingPointCut cut{pixelsPerMetre,
                               float(options_.buildingPointsUnderSse * options_.lod.maxScreenSpaceError)};
    OcclusionGrid tiles;
    bool drawnSinceTiles = false; // the tiles are built again only after more was drawn
    for (uint8_t ring = 0; ring < kVolumeRings; ++ring) {
        std::vector<VolumeDraw> draws;
        for (const VolumeDraw& draw : volumes)
            if (draw.ring == ring) draws.push_back(draw);
        if (draws.empty()) continue;
        if (test && (drawnSinceTiles || !tiles.tiles.empty())) {
            if (drawnSinceTiles) {
                volumeTiles_.build(target_.depthTexture(), false);
                tiles = occlusionGrid(volumeTiles_.read(), volumeTiles_.columns(), volumeTiles_.rows());
                drawnSinceTiles = false;
            }
            std::erase_if(draws, [&](const VolumeDraw& draw) {
                const bool hidden = volumeHidden(draw, pose.position, occlusion, tiles);
                stats.volumesOccluded += hidden;
                return hidden;
            });
            timer.restart(); // the tiles belong to no pass
        }
        for (VolumeDraw& draw : draws) {
            draw.mesh = &volumes_.acquire(draw.batch, draw.inset, draw.lod0Blend < 1.0f);
            // Building by building too: at street level a batch that shows at all often shows
            // a few of its buildings only, and with multisampling llvmpipe shades every
            // fragment it rasterises, hidden or not (it skips hidden ones only at one sample).
            selectBuildingRuns(draw, pose.position, occlusion,
                               test && !tiles.tiles.empty() ? &tiles : nullptr, cut, stats);
        }
        drawVolumes(draws, pose, pixelsPerMetre, stats, timer);
        drawnSinceTiles = drawnSinceTiles || !draws.empty();
    }
}

bool CityRenderer::volumeHidden(const VolumeDraw& draw, const glm::dvec3& camera,
                                const shared::CullFrame& occlusion, const OcclusionGrid& tiles) const {
    glm::vec3 lo, hi;
    if (draw.mesh) {
        const glm::vec3 origin(draw.mesh->cellOrigin - camera);
        lo = origin + draw.mesh->boundsMin, hi = origin + draw.mesh->boundsMax;
    } else {
        // Not built yet: the cell's bounds, which the scheduler's frustum test already trusts
        // to hold the cell's buildings.
        const cells::CellBounds* cell = catalog_.index().boundsOf(catalog_.batch(draw.batch).cell);
        if (!cell) return false;
        lo = glm::vec3(glm::dvec3(cell->lo, cell->zMin) - camera);
        hi = glm::vec3(glm::dvec3(cell->hi, cell->zMax) - camera);
    }
    return tilesHideBox(occlusion, &tiles, lo, hi);
}

void CityRenderer::selectBuildingRuns(VolumeDraw& draw, const glm::dvec3& camera,
                                      const shared::CullFrame& occlusion, const OcclusionGrid* tiles,
                                      const BuildingPointCut& cut, FrameStats& stats) const {
    draw.pointRuns.clear();
    const std::vector<render::VolumeBuilding>& buildings = draw.mesh->buildings;
    if (buildings.empty()) {
        draw.runs = {{0u, draw.mesh->indexCount}};
        return;
    }
    const glm::vec3 origin(draw.mesh->cellOrigin - camera);
    // Points are LOD0's far form: not for the shells under terminals, nor LOD1's walls.
    const bool points = draw.mesh->pointBuffer != 0 && draw.textured && draw.lod0Blend >= 1.0f;
    std::vector<uint32_t> kept;
    kept.reserve(buildings.size());
    for (uint32_t b = 0; b < buildings.size(); ++b) {
        if (tiles && tilesHideBox(occlusion, tiles, origin + buildings[b].boundsMin,
                                  origin + buildings[b].boundsMax)) {
            ++stats.volumeBuildingsOccluded;
            continue;
        }
        if (points && buildingIsPoint(buildings[b], origin, cut)) {
            appendRun(draw.pointRuns, b, 1);
            ++stats.volumeBuildingPoints;
            continue;
        }
        kept.push_back(b);
    }
    // Beyond LOD1's distance a building is a few pixels: the depth order spares little shading
    // there, and sorted, the overview's buildings split into about one draw each
    // (docs/BENCHMARKS.md, "The overview: far base volumes in the mesh's order...").
    draw.runs = draw.ring < 2 ? nearestFirstRuns(buildings, kept, origin) : buildingRuns(buildings, kept);
}

// One draw per run; a single run is the common case (the whole mesh, or every building left).
void CityRenderer::drawRuns(const VolumeDraw& draw, FrameStats& stats) {
    const VolumeBuffers& gpu = draw.mesh->gpu;
    gl::glBindVertexArray(gpu.vao);
    if (draw.runs.size() == 1) {
        gl::glDrawElements(GL_TRIANGLES, GLsizei(draw.runs[0].y), gpu.indexType,
                           reinterpret_cast<const void*>(uintptr_t(draw.runs[0].x) * gpu.indexSize));
    } else {
        std::vector<GLsizei> counts;
        std::vector<const void*> offsets;
        for (const glm::uvec2& run : draw.runs) {
            counts.push_back(GLsizei(run.y));
            offsets.push_back(reinterpret_cast<const void*>(uintptr_t(run.x) * gpu.indexSize));
        }
        gl::glMultiDrawElements(GL_TRIANGLES, counts.data(), gpu.indexType, offsets.data(),
                                GLsizei(counts.size()));
    }
    for (const glm::uvec2& run : draw.runs) stats.triangles += run.y / 3;
    ++stats.draws;
}

void CityRenderer::drawBuildingPoints(const std::vector<VolumeDraw>& volumes, const glm::dvec3& camera,
                                      float screenScale, FrameStats& stats) {
    bool bound = false;
    for (const VolumeDraw& draw : volumes) {
        if (draw.pointRuns.empty()) continue;
        if (!bound) {
            programs_->buildingPoint.use();
            programs_->buildingPoint.set("screenScale", screenScale);
            gl::glBindVertexArray(impostorVao_); // attribute-less: the points are read by gl_VertexID
            gl::glEnable(GL_PROGRAM_POINT_SIZE);
            bound = true;
        }
        programs_->buildingPoint.set("cellOffset", glm::vec3(draw.mesh->cellOrigin - camera));
        programs_->buildingPoint.set("batch", draw.batch);
        gl::glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBuildingPointBinding, draw.mesh->pointBuffer);
        std::vector<GLint> firsts;
        std::vector<GLsizei> counts;
        for (const glm::uvec2& run : draw.pointRuns) {
            firsts.push_back(GLint(run.x));
            counts.push_back(GLsizei(run.y));
        }
        gl::glMultiDrawArrays(GL_POINTS, firsts.data(), counts.data(), GLsizei(counts.size()));
        ++stats.draws;
    }
    if (bound) gl::glDisable(GL_PROGRAM_POINT_SIZE);
}

void CityRenderer::drawVolumes(const std::vector<VolumeDraw>& volumes, const scene::CameraPose& pose,
                               float screenScale, FrameStats& stats, PassTimer& timer) {
    const glm::dvec3& camera = pose.position;
    // LOD0 first, plain or textured, then LOD1 grammar by grammar.
    const render::ShaderProgram* bound = nullptr;
    for (const VolumeDraw& draw : volumes) {
        if (draw.mesh->indexCount == 0 || draw.runs.empty() || draw.lod0Blend < 1.0f) continue;
        const glm::vec3 offset(draw.mesh->cellOrigin - camera);
        const bool mean = draw.textured && options_.shadeFarWallsAtMean &&
                          wallTextureIsMean(offset + draw.mesh->boundsMin, offset + draw.mesh->boundsMax,
                                            glm::vec3(pose.forward), screenScale);
        const render::ShaderProgram& program = !draw.textured ? programs_->volume
                                               : mean         ? programs_->meanWallVolume
                                                              : programs_->texturedVolume;
        if (bound != &program) program.use(), bound = &program;
        program.set("cellOffset", offset);
        drawRuns(draw, stats);
        stats.volumesShadedAtMean += mean;
    }
    drawBuildingPoints(volumes, camera, screenScale, stats);
    timer.end(DrawPass::Lod0);
    for (const auto& [grammar, program] : programs_->lod1) {
        bool bound = false;
        for (const VolumeDraw& draw : volumes) {
            if (draw.mesh->indexCount == 0 || draw.runs.empty() || draw.lod0Blend >= 1.0f ||
                draw.mesh->grammar != grammar)
                continue;
            if (!bound) {
                program.use();
                impostorTextures_.bind(program, 0);
                program.set("shapeBase", shapes_.shapeBase(grammar));
                program.set("centralView", centralView_);
                gl::glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, shapes_.shapeBuffer());
                gl::glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, sphereBuffer_);
                bound = true;
            }
            program.set("cellOffset", glm::vec3(draw.mesh->cellOrigin - camera));
            program.set("lod0Blend", draw.lod0Blend);
            gl::glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 11, draw.mesh->parameterBuffer);
            gl::glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 12, draw.mesh->elementBuffer);
            drawRuns(draw, stats);
        }
    }
    gl::glBindVertexArray(0);
    timer.end(DrawPass::Lod1);
}

} // namespace hexlod::lod
