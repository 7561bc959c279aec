// The frame: scheduling, upload, the cull pass and the order of the draws (the base volumes' in
// volume_draws.cpp, the terminal sets' in terminal_draws.cpp).
#include "hexlod/lod/city_renderer.h"
#include "city_renderer_programs.h"
#include "hexlod/lod/coarse_meshes.h"
#include "hexlod/lod/lod1_codegen.h"
#include "hexlod/render/gl_api.h"
#include "hexlod/render/gpu_types.h"
#include "hexlod/render/mesh_vertex_format.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

namespace hexlod::lod {
namespace {

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// std140 mirror of FrameBlock in frame.glsl.
struct FrameUniforms {
    glm::mat4 viewProjection;
    glm::vec4 sunDirection;
    glm::vec4 sunColour;
    glm::vec4 skyColour;
    glm::vec4 viewport;
};

constexpr glm::vec3 kSky(0.62f, 0.72f, 0.84f);

// The draw-list records as per-instance attributes (gpu_types.h names their locations).
void setTerminalInstanceFormat(uint32_t vao, uint32_t binding) {
    const render::VertexAttribute attributes[] = {
        {HEXLOD_ATTRIBUTE_INSTANCE_POSITION, 3, GL_FLOAT, false, 0},
        {HEXLOD_ATTRIBUTE_INSTANCE_BUILDING, 1, GL_FLOAT, false, 12}, // the transition factor in draw lists
        {HEXLOD_ATTRIBUTE_INSTANCE_ORIENTATION, 4, GL_SHORT, true, 16},
        {HEXLOD_ATTRIBUTE_INSTANCE_SIZE, 2, GL_HALF_FLOAT, false, 24},
        {HEXLOD_ATTRIBUTE_INSTANCE_DEPTH, 1, GL_HALF_FLOAT, false,
         30}, // 28 holds the shape, which no shader reads
    };
    render::setVertexAttributes(vao, binding, attributes);
    gl::glVertexArrayBindingDivisor(vao, binding, 1);
}

// Reversed-Z perspective for zero-to-one clip depth: near maps to 1, far to 0.
glm::mat4 reversedPerspective(double fovY, double aspect, double nearPlane, double farPlane) {
    const double f = 1.0 / std::tan(0.5 * fovY);
    glm::dmat4 p(0.0);
    p[0][0] = f / aspect;
    p[1][1] = f;
    p[2][2] = nearPlane / (farPlane - nearPlane);
    p[2][3] = -1.0;
    p[3][2] = nearPlane * farPlane / (farPlane - nearPlane);
    return glm::mat4(p);
}

} // namespace

const char* renderModeName(RenderMode mode) {
    switch (mode) {
    case RenderMode::Lod:
        return "lod";
    case RenderMode::AllLod4:
        return "lod4";
    case RenderMode::AllLod3:
        return "lod3";
    case RenderMode::AllLod2:
        return "lod2";
    case RenderMode::AllLod1:
        return "lod1";
    case RenderMode::AllLod0:
        return "lod0";
    }
    return "?";
}

bool parseRenderMode(std::string_view name, RenderMode& out) {
    for (RenderMode mode : {RenderMode::Lod, RenderMode::AllLod4, RenderMode::AllLod3, RenderMode::AllLod2,
                            RenderMode::AllLod1, RenderMode::AllLod0}) {
        if (name == renderModeName(mode)) {
            out = mode;
            return true;
        }
    }
    return false;
}

CityRenderer::CityRenderer(cells::BatchCatalog& catalog, cache::TerminalSetCache& cache,
                           const render::TerminalMeshLibrary& meshes, const SceneImpostors* impostors,
                           CityRendererOptions options)
    : catalog_(catalog), cache_(cache), meshes_(meshes), impostors_(impostors), options_(std::move(options)),
      volumes_(catalog, options_.volumeBudgetBytes) {}

CityRenderer::~CityRenderer() {
    for (uint32_t buffer : {sphereBuffer_, frameBuffer_})
        if (buffer) gl::glDeleteBuffers(1, &buffer);
    for (uint32_t vao : {lod4Vao_, impostorVao_})
        if (vao) gl::glDeleteVertexArrays(1, &vao);
}

bool CityRenderer::init(std::string& error) {
    cells::SchedulerOptions scheduling;
    scheduling.lod = options_.lod;
    scheduling.workers = options_.schedulerWorkers;
    scheduling.prefetchInBackground = true; // with no workers; they prefetch themselves
    scheduling.maxBatchesPerFrame = options_.maxBatchesPerFrame;
    scheduling.onBackgroundSet = [bounds = preparedBounds_](uint64_t key, const auto& set) {
        bounds->prepare(key, set);
    };
    // Trees: geometry near the camera, billboards beyond; the reference draws every tree as
    // geometry and the forced coarse modes every tree as a billboard.
    const bool speciesImpostors = impostors_ && !impostors_->species.empty();
    treeError_ = options_.lod.treeGeometricError;
    if (!speciesImpostors || options_.mode == RenderMode::AllLod4) treeError_ = 0.0;
    scheduling.treeGeometricError = options_.mode == RenderMode::Lod ? treeError_ : 0.0;
    if (options_.mode == RenderMode::AllLod4 || options_.mode == RenderMode::AllLod3 ||
        options_.mode == RenderMode::AllLod2) {
        scheduling.forcedLod = cells::CellLod::Terminals;
    }
    if (options_.mode == RenderMode::AllLod3 || options_.mode == RenderMode::AllLod2) {
        scheduling.treeGeometricError = 1e9; // billboards only: tree batches are never wanted
    } else if (options_.mode == RenderMode::AllLod1 || options_.mode == RenderMode::AllLod0) {
        scheduling.forcedLod = cells::CellLod::Extruded;
    }
    try {
        scheduler_ = std::make_unique<cells::Scheduler>(catalog_, cache_, scheduling);
    } catch (const std::invalid_argument& e) {
        error = std::string("LOD profile: ") + e.what();
        return false;
    }
    if (!render::Framebuffer::create({options_.width, options_.height, {GL_RGBA16F}, true, options_.samples},
                                     target_, error))
        return false;
    if (!arena_.create(options_.arenaRecords, error) || !cull_.init(error)) return false;
    programs_ = std::make_unique<Programs>();
    render::ShaderLibrary library = lodShaderLibrary();
    programs_->lod4 = render::ShaderProgram::build(
        library,
        {{render::ShaderStage::Vertex, "terminal_mesh.vert"}, {render::ShaderStage::Fragment, "lit.frag"}},
        "", error);
    if (!programs_->lod4.valid()) return false;
    // volume.frag's VOLUME_SHADING.
    const std::pair<render::ShaderProgram*, const char*> volumes[] = {{&programs_->volume, "0"},
                                                                      {&programs_->ground, "1"},
                                                                      {&programs_->texturedVolume, "2"},
                                                                      {&programs_->meanWallVolume, "3"}};
    for (const auto& [volume, shading] : volumes) {
        *volume = render::ShaderProgram::build(
            library,
            {{render::ShaderStage::Vertex, "volume.vert"}, {render::ShaderStage::Fragment, "volume.frag"}},
            std::string("#define VOLUME_SHADING ") + shading + "\n", error);
        if (!volume->valid()) return false;
    }
    programs_->buildingPoint = render::ShaderProgram::build(
        library,
        {{render::ShaderStage::Vertex, "building_point.vert"}, {render::ShaderStage::Fragment, "point.frag"}},
        "", error);
    if (!programs_->buildingPoint.valid()) return false;

    // The reference draws every terminal's full mesh; only the LOD system may draw a coarser one.
    const std::vector<CoarseMesh> coarse =
        options_.mode == RenderMode::Lod ? coarseMeshes(catalog_, meshes_) : std::vector<CoarseMesh>{};
    shapes_.upload(meshes_, coarse);
    coarseNote_ = describeCoarseMeshes(coarse, shapes_);
    ground_.upload(catalog_.scene().roads, catalog_.cellOrigin(catalog_.index().cells().empty()
                                                                   ? cells::HexCoord{}
                                                                   : catalog_.index().cells().front().cell));
    if (impostors_ && !impostors_->facades.empty()) {
        const impostor::ViewLayout& layout = impostors_->facades.front().layout;
        std::vector<const impostor::ImpostorAtlas*> atlases;
        std::vector<glm::vec4> spheres;
        for (const impostor::ImpostorAtlas& atlas : impostors_->facades) {
            atlases.push_back(&atlas);
            spheres.emplace_back(atlas.centre, atlas.radius);
        }
        impostor::ViewLookup lookup(layout);
        if (!impostorTextures_.upload(layout, atlases, lookup.buildTable(impostor::kFacadeTableResolution),
                                      error))
            return false;
        impostor::ViewWeights front;
        lookup.nearestViews(glm::vec3(0, 0, 1), front);
        centralView_ = front.views[0];
        for (uint32_t g = 0; g < impostors_->facadeLayer.size(); ++g)
            for (size_t s = 0; s < impostors_->facadeLayer[g].size(); ++s)
                shapes_.setImpostorLayer(shapes_.shapeBase(g) + uint32_t(s), impostors_->facadeLayer[g][s]);
        gl::glCreateBuffers(1, &sphereBuffer_);
        gl::glNamedBufferStorage(sphereBuffer_, GLsizeiptr(spheres.size() * sizeof(glm::vec4)),
                                 spheres.data(), 0);
        programs_->impostor =
            render::ShaderProgram::build(library,
                                         {{render::ShaderStage::Vertex, "impostor_terminal.vert"},
                                          {render::ShaderStage::Fragment, "impostor_terminal.frag"}},
                                         "", error);
        if (!programs_->impostor.valid()) return false;
        programs_->impostorWall =
            render::ShaderProgram::build(library,
                                         {{render::ShaderStage::Vertex, "impostor_wall.vert"},
                                          {render::ShaderStage::Fragment, "impostor_wall.frag"}},
                                         "", error);
        if (!programs_->impostorWall.valid()) return false;
        // One LOD1 interpreter per building grammar that has buildings.
        for (uint32_t g = 0; g < catalog_.scene().buildingGrammars.size(); ++g) {
            const scene::GrammarBuildings& grammar = catalog_.scene().buildingGrammars[g];
            if (grammar.buildings.empty()) continue;
            render::ShaderLibrary withGrammar = library;
            withGrammar.add("lod1_grammar.glsl", generateLod1Grammar(grammar.grammar));
            render::ShaderProgram program = render::ShaderProgram::build(
                withGrammar,
                {{render::ShaderStage::Vertex, "volume.vert"}, {render::ShaderStage::Fragment, "lod1.frag"}},
                "", error);
            if (!program.valid()) {
                error = "LOD1 interpreter of grammar '" + grammar.name + "': " + error;
                return false;
            }
            programs_->lod1.emplace(g, std::move(program));
        }
    }
    const size_t buildingGrammars = catalog_.scene().buildingGrammars.size();
    shapeTree_.assign(shapes_.shapeCount(), 0);
    for (uint32_t g = uint32_t(buildingGrammars); g < catalog_.index().grammarCount(); ++g)
        for (size_t s = 0; s < meshes_.shapeCount(g); ++s) shapeTree_[shapes_.shapeBase(g) + s] = 1;
    shapes_.commit();
    if (!trees_.init(catalog_, impostors_, ground_.origin(), options_.fitTreeBillboards, error)) return false;
    if (!depthTiles_.init(options_.width, options_.height, options_.samples, kDepthTileSize, error) ||
        !volumeTiles_.init(options_.width, options_.height, options_.samples, kVolumeTileSize, error))
        return false;

    gl::glCreateBuffers(1, &frameBuffer_);
    gl::glNamedBufferStorage(frameBuffer_, sizeof(FrameUniforms), nullptr, GL_DYNAMIC_STORAGE_BIT);
    gl::glCreateVertexArrays(1, &lod4Vao_);
    shapes_.bindVertices(lod4Vao_, 0);
    setTerminalInstanceFormat(lod4Vao_, 1);
    gl::glCreateVertexArrays(1, &impostorVao_); // attribute-less: impostors pull their entries
    return true;
}

FrameStats CityRenderer::render(const scene::CameraPose& given, double timeSeconds, double nearPlane,
                                double farPlane) {
    const auto frameStart = Clock::now();
    const scene::CameraPose pose = scene::usablePose(given);
    FrameStats stats;
    stats.frame = frame_++;
    const double aspect = double(options_.width) / double(options_.height);

    // 1. Cells and their LOD; batches the frame needs are generated here (synchronous mode).
    cells::Camera camera;
    camera.position = pose.position;
    camera.forward = pose.forward;
    camera.up = pose.up;
    camera.fovY = pose.fovY;
    camera.viewportWidth = options_.width;
    camera.viewportHeight = options_.height;
    camera.nearPlane = nearPlane;
    camera.farPlane = farPlane;
    const cache::CacheStats cacheBefore = cache_.stats();
    auto stageStart = Clock::now();
    const cells::FrameDecision decision = scheduler_->update(camera, timeSeconds);
    stats.scheduleMs = millisecondsSince(stageStart);
    const cache::CacheStats cacheScheduled = cache_.stats();
    stats.generationMs =
        (cacheScheduled.generationSecondsTotal - cacheBefore.generationSecondsTotal) * 1000.0;

    // 2. Upload: ready terminal sets into the arena; base volumes for extruded cells, for the
    // shells under terminals, and for batches still being generated (so nothing vanishes).
    stageStart = Clock::now();
    arena_.beginFrame(stats.frame);
    volumes_.beginFrame(stats.frame);
    CullInputs inputs;
    inputs.camera = pose.position;
    inputs.shapeCount = shapes_.shapeCount();
    inputs.shapeImpostor = shapes_.impostorFlags();
    inputs.shapeTree = shapeTree_;
    inputs.shapeCoarse = shapes_.coarseTable();
    inputs.maxListRecords = cull_.maxListRecords();
    inputs.trees = &trees_.trees();
    inputs.treeBuffer = trees_.treeBuffer();
    std::vector<std::pair<uint32_t, bool>> billboards; // tree batch, every tree a billboard
    std::vector<std::shared_ptr<const grammar::TerminalSet>> pinned;
    std::vector<VolumeDraw> volumes;
    const size_t buildingGrammars = catalog_.scene().buildingGrammars.size();
    // LOD0 suffices for an extruded cell whose LOD0 error stays under the budget; LOD1 is
    // counted apart for the reports.
    const double lod1Distance =
        lodDistance(options_.lod.geometricError[0], options_.lod, pose.fovY, options_.height);
    // Nearest cells first: when the arena cannot hold every set in view, the ones it rejects
    // (drawn at LOD1 or LOD0) are the farthest.
    std::vector<const cells::CellDecision*> nearestFirst;
    for (const cells::CellDecision& cell : decision.cells) nearestFirst.push_back(&cell);
    std::stable_sort(nearestFirst.begin(), nearestFirst.end(),
                     [](const auto* a, const auto* b) { return a->distance < b->distance; });
    for (const cells::CellDecision* nearest : nearestFirst) {
        const cells::CellDecision& cell = *nearest;
        ++stats.visibleCells;
        if (cell.lod == cells::CellLod::Terminals) {
            ++stats.cellsPerLod[4];
            for (uint32_t b : cell.ready) {
                // With workers the frame never reads the disk: a set evicted since the
                // scheduler saw it waits for the next frame's request, as a pending batch.
                std::shared_ptr<const grammar::TerminalSet> set = options_.schedulerWorkers > 0
                                                                      ? cache_.findInMemory(catalog_.key(b))
                                                                      : cache_.find(catalog_.key(b));
                const uint64_t digest = catalog_.key(b).digest();
                const ArenaBatch* resident = nullptr;
                if (set)
                    resident = arena_.acquire(digest, *set,
                                              arena_.resident(digest) ? std::vector<PageBounds>{}
                                                                      : preparedBounds_->take(digest));
                const bool building = catalog_.batch(b).grammar < buildingGrammars;
                if (!resident) {
                    ++(set ? stats.batchesRejected : stats.batchesPending);
                    if (building)
                        volumes.push_back({&volumes_.acquire(b, 0.0f), b, 0.0f, true, 1.0f, 0});
                    else
                        billboards.emplace_back(b, true);
                    continue;
                }
                if (!building) billboards.emplace_back(b, false);
                inputs.batches.push_back({set.get(), &resident->pages,
                                          catalog_.cellOrigin(catalog_.batch(b).cell),
                                          shapes_.shapeBase(catalog_.batch(b).grammar), &resident->bounds});
                pinned.push_back(std::move(set));
                ++stats.batchesDrawn;
                if (building) volumes.push_back({&volumes_.acquire(b, 0.5f), b, 0.5f, false, 1.0f, 0});
            }
            for (uint32_t b : cell.requested) {
                ++stats.batchesPending;
                if (catalog_.batch(b).grammar < buildingGrammars)
                    volumes.push_back({&volumes_.acquire(b, 0.0f), b, 0.0f, true, 1.0f, 0});
                else
                    billboards.emplace_back(b, true);
            }
            if (!cell.treesAsTerminals) {
                // Tree batches left out of the cell's batches: every tree a billboard.
                const uint32_t first = catalog_.firstBatchOf(cell.cell);
                const uint32_t count = uint32_t(catalog_.index().batchesOf(cell.cell).size());
                for (uint32_t b = first; b < first + count; ++b)
                    if (catalog_.batch(b).grammar >= buildingGrammars) billboards.emplace_back(b, true);
            }
        } else {
            // LOD1 within its distance, blending into LOD0 over the band before it.
            float lod0Blend = 1.0f;
            if (!programs_->lod1.empty() && options_.mode != RenderMode::AllLod0) {
                const double start = lod1Distance * (1.0 - options_.transitionBand);
                lod0Blend = options_.mode == RenderMode::AllLod1 ? 0.0f
                            : cell.distance >= lod1Distance      ? 1.0f
                            : cell.distance <= start
                                ? 0.0f
                                : float((cell.distance - start) / (lod1Distance - start));
            }
            ++stats.cellsPerLod[lod0Blend < 1.0f ? 1 : 0];
            const uint32_t first = catalog_.firstBatchOf(cell.cell);
            const uint32_t count = uint32_t(catalog_.index().batchesOf(cell.cell).size());
            for (uint32_t b = first; b < first + count; ++b) {
                if (catalog_.batch(b).grammar >= buildingGrammars) {
                    billboards.emplace_back(b, true);
                    continue;
                }
                volumes.push_back({volumes_.find(b, 0.0f), b, 0.0f, true, lod0Blend,
                                   uint8_t(cell.distance < lod1Distance ? 1 : 2)});
                ++stats.batchesDrawn;
            }
        }
    }
    stats.uploadMs = millisecondsSince(stageStart);
    stats.batchesUploaded = arena_.stats().uploads;
    stats.uploadsPrepared = arena_.stats().preparedUploads;

    // 3. The opaque base volumes and ground, which hide what stands behind them: drawn first,
    // so that the cull pass can drop hidden terminals before any of their work is done.
    stageStart = Clock::now();
    const glm::dvec3 right = glm::normalize(glm::cross(pose.forward, pose.up));
    const glm::dvec3 up = glm::cross(right, pose.forward);
    glm::mat4 view(1.0f);
    for (int c = 0; c < 3; ++c) {
        view[c][0] = float(right[c]);
        view[c][1] = float(up[c]);
        view[c][2] = float(-pose.forward[c]);
    }
    FrameUniforms uniforms;
    uniforms.viewProjection = reversedPerspective(pose.fovY, aspect, nearPlane, farPlane) * view;
    uniforms.sunDirection = glm::vec4(glm::normalize(glm::vec3(0.45f, -0.55f, 0.7f)), 0.35f);
    uniforms.sunColour = glm::vec4(1.0f, 0.97f, 0.9f, 0.0f);
    uniforms.skyColour = glm::vec4(kSky, 1.0f / 9000.0f);
    uniforms.viewport = glm::vec4(float(options_.width), float(options_.height), 1.0f / float(options_.width),
                                  1.0f / float(options_.height));
    gl::glNamedBufferSubData(frameBuffer_, 0, sizeof uniforms, &uniforms);
    gl::glBindBufferBase(GL_UNIFORM_BUFFER, 1, frameBuffer_);

    gl::glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    target_.bind();
    target_.clear(kSky.r, kSky.g, kSky.b, 1.0f, 0.0f);
    gl::glEnable(GL_DEPTH_TEST);
    gl::glDepthFunc(GL_GREATER);
    gl::glDepthMask(GL_TRUE);
    gl::glDisable(GL_BLEND);
    gl::glEnable(GL_CULL_FACE);
    gl::glCullFace(GL_BACK);
    PassTimer timer(options_.passClock, stats.passMs);
    if (depthTiles_.valid()) depthTiles_.clearCounts();
    drawVolumeRings(volumes, pose, nearPlane, farPlane, stats, timer);
    stats.triangles += ground_.draw(programs_->ground, pose.position);
    stats.draws += 2;
    timer.end(DrawPass::Ground);
    stats.drawMs = millisecondsSince(stageStart);

    // 4. The cull and LOD pass, against the depth of those occluders.
    stageStart = Clock::now();
    const cells::Frustum frustum(pose.position, pose.forward, pose.up, pose.fovY, aspect, nearPlane,
                                 farPlane);
    inputs.frame = makeCullFrame(frustum, options_.lod, pose.fovY, options_.height, options_.transitionBand,
                                 impostorsDrawn());
    if (options_.mode == RenderMode::AllLod3)
        inputs.frame.lodDistance = glm::vec4(0.0f, std::numeric_limits<float>::max(), 0.0f, 1.0f);
    if (options_.mode == RenderMode::AllLod2) inputs.frame.lodDistance = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    const double treeCut = treeError_ > 0.0 && !trees_.empty() && trees_.hasImpostors()
                               ? lodDistance(treeError_, options_.lod, pose.fovY, options_.height)
                               : -1.0;
    setTreeCut(inputs.frame, treeCut, trees_.origin(), pose.position);
    if (options_.mode == RenderMode::Lod)
        setCoarseMeshes(inputs.frame, options_.lod, pose.fovY, options_.height);
    std::vector<float> occlusionTiles;
    if (options_.dropHidden && (!inputs.batches.empty() || !billboards.empty())) {
        depthTiles_.build(target_.depthTexture(), false);
        occlusionTiles = depthTiles_.read();
        setOcclusion(inputs.frame, pose.forward, pose.up, pose.fovY, nearPlane, farPlane, options_.width,
                     options_.height, depthTiles_.columns(), depthTiles_.rows(), kDepthTileSize);
        inputs.occlusionTexture = depthTiles_.texture();
        inputs.occlusionTiles = &occlusionTiles;
    }
    cull_.run(inputs, arena_.buffer(), shapes_.meshes());
    stats.cullTerminals = cull_.pageStats().terminals;
    stats.cullSkippedTerminals = cull_.pageStats().skippedTerminals;
    stats.cullOccludedTerminals = cull_.pageStats().occludedTerminals;
    stats.cullFacingAwayTerminals = cull_.pageStats().facingAwayTerminals;
    stats.cullBillboardTerminals = cull_.pageStats().billboardTerminals;
    stats.cullMs = millisecondsSince(stageStart);

    // 5. The rest of the draws.
    stageStart = Clock::now();
    timer.restart();
    drawTerminalMeshes(timer);
    const bool lod3Tiles = drawImpostors(glm::mat4(glm::inverse(glm::dmat4(uniforms.viewProjection))), timer);
    if (trees_.hasImpostors() && !billboards.empty()) {
        TreeFrame trees;
        trees.cull = &inputs.frame;
        trees.occlusionTiles = inputs.occlusionTiles;
        trees.screenScale = float(screenScale(pose.fovY, options_.height));
        trees.pointDiameter = float(options_.treePointsUnderSse * options_.lod.maxScreenSpaceError);
        const auto [submitted, points] = trees_.prepare(billboards, trees);
        stats.treeBillboards = submitted;
        stats.treePoints = points;
        gl::glBindBufferBase(GL_UNIFORM_BUFFER, 0, cull_.frameBuffer());
        // The billboards are tested against the tiles LOD3 was tested against: built again
        // after LOD3, they would wait for its rasterisation, which the trees' setup overlaps
        // instead. A billboard that LOD3 hides then fails the depth test pixel by pixel.
        if (!lod3Tiles) depthTiles_.build(target_.depthTexture(), true);
        for (const render::ShaderProgram& program : trees_.billboardPrograms()) {
            depthTiles_.bind(program, kDepthTilesUnit, TileTest::TreeBillboards, options_.dropHidden);
            program.set("alphaToCoverage", uint32_t(options_.samples > 1));
        }
        if (options_.samples > 1) gl::glEnable(GL_SAMPLE_ALPHA_TO_COVERAGE);
        stats.draws += trees_.drawBillboards(trees);
        gl::glDisable(GL_SAMPLE_ALPHA_TO_COVERAGE);
        stats.draws += trees_.drawPoints(trees);
        stats.triangles += 2ull * submitted;
    }
    timer.end(DrawPass::Trees);
    stats.drawMs += millisecondsSince(stageStart);

    stageStart = Clock::now();
    gl::glFinish();
    gl::glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    gl::glDepthFunc(GL_LESS);
    stats.gpuWaitMs = millisecondsSince(stageStart);
    timer.collect();
    // The cull's counts are statistics only: read once the frame is done, so that the CPU
    // does not wait for the cull between submitting it and the draws it feeds.
    countCulledTerminals(stats);
    if (depthTiles_.valid()) {
        const auto dropped = depthTiles_.dropped();
        stats.treeBillboardsOccluded = dropped[size_t(TileTest::TreeBillboards)];
        stats.lod3Occluded = dropped[size_t(TileTest::Lod3Impostors)];
    }
    stats.frameMs = millisecondsSince(frameStart);

    const cache::CacheStats cacheAfter = cache_.stats();
    stats.diskLoadMs = (cacheAfter.diskLoadSecondsTotal - cacheBefore.diskLoadSecondsTotal) * 1000.0;
    stats.diskStoreMs = (cacheAfter.diskStoreSecondsTotal - cacheBefore.diskStoreSecondsTotal) * 1000.0;
    stats.cacheBytes = cacheAfter.memoryBytes;
    stats.cacheLookups = cacheAfter.lookups - cacheBefore.lookups;
    stats.cacheHits = cacheAfter.hits - cacheBefore.hits;
    stats.volumesBuilt = volumes_.stats().built;
    stats.volumeBytes = volumes_.stats().residentBytes;
    stats.gpuBytes = arena_.byteSize() + arena_.stats().pageTableBytes + preparedBounds_->byteSize() +
                     cull_.byteSize() + shapes_.byteSize() + stats.volumeBytes + ground_.byteSize() +
                     trees_.byteSize() + depthTiles_.byteSize() + volumeTiles_.byteSize() +
                     impostorQuads_.byteSize() +
                     uint64_t(options_.width) * options_.height * 12 * options_.samples;
    stats.impostorBytes = impostorTextures_.byteSize();
    return stats;
}

std::string CityRenderer::summary() const {
    return "LOD1 shaders: " + std::to_string(programs_ ? programs_->lod1.size() : 0) + " grammar" +
           (programs_ && programs_->lod1.size() == 1 ? "" : "s");
}

std::string CityRenderer::arenaNote() const {
    const ArenaStats arena = arena_.stats();
    if (arena.capacityRecords >= arena.requestedRecords) return "";
    char text[200];
    std::snprintf(text, sizeof text,
                  "terminal arena: %.2f M records of the %.2f M asked, capped by the GL's largest shader "
                  "storage block (%llu MiB); terminal sets beyond it draw at LOD1 or LOD0 (batches_rejected)",
                  arena.capacityRecords / 1e6, arena.requestedRecords / 1e6,
                  (unsigned long long)(arena_.byteSize() >> 20));
    return text;
}

} // namespace hexlod::lod
