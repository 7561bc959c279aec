// Driving the cull and finalize compute passes.
#include "hexlod/lod/gpu_cull.h"
#include "hexlod/impostor/impostor_textures.h"
#include "hexlod/lod/terminal_arena.h"
#include "hexlod/lod/wall_texture_mean.h"
#include "hexlod/render/gl_api.h"

#include <algorithm>

std::span<const hexlod::render::ShaderFile> hexlodLodShaders();

namespace hexlod::lod {
namespace {

constexpr uint32_t kWorkgroupSize = 64; // cull_finalize.comp's local size

// The GLSL binding of each buffer (terminal_cull.comp, cull_finalize.comp).
constexpr uint32_t kBindings[] = {0, 1, 2, 3, 4, 5, 6, 7, 11, 12, 13, 15};
// The occlusion tiles' texture unit: every pass after the cull binds its own textures.
constexpr uint32_t kOcclusionUnit = 0;

} // namespace

render::ShaderLibrary lodShaderLibrary() {
    render::ShaderLibrary library = impostor::impostorShaderLibrary();
    library.add(hexlodLodShaders());
    library.add("wall_texture_sizes.glsl", wallTextureSizesGlsl());
    return library;
}

GpuCull::~GpuCull() {
    for (Buffer& buffer : buffers_)
        if (buffer.id) gl::glDeleteBuffers(1, &buffer.id);
}

bool GpuCull::init(std::string& error) {
    GLint64 maxBlockBytes = 0;
    gl::glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlockBytes);
    maxListRecords_ = uint64_t(maxBlockBytes) / sizeof(gpu::GpuTerminal);
    render::ShaderLibrary library = lodShaderLibrary();
    cull_ = render::ShaderProgram::build(library, {{render::ShaderStage::Compute, "terminal_cull.comp"}}, "",
                                         error);
    if (!cull_.valid()) return false;
    finalize_ = render::ShaderProgram::build(library, {{render::ShaderStage::Compute, "cull_finalize.comp"}},
                                             "", error);
    return finalize_.valid();
}

void GpuCull::reserve(BufferIndex index, uint64_t bytes) {
    Buffer& buffer = buffers_[index];
    bytes = std::max<uint64_t>(bytes, 256);
    if (buffer.capacity >= bytes) return;
    // Growth keeps a quarter's headroom at most, not a doubling: the draw lists grow with the
    // terminals in view up to the arena's size (128 MiB on llvmpipe), where doubling would hold
    // up to twice what a frame can use.
    uint64_t capacity = std::max(bytes, std::min(buffer.capacity * 2, bytes + bytes / 4));
    if (buffer.id) gl::glDeleteBuffers(1, &buffer.id);
    gl::glCreateBuffers(1, &buffer.id);
    gl::glNamedBufferStorage(buffer.id, GLsizeiptr(capacity), nullptr, GL_DYNAMIC_STORAGE_BIT);
    buffer.capacity = capacity;
}

uint64_t GpuCull::byteSize() const {
    uint64_t total = 0;
    for (const Buffer& buffer : buffers_) total += buffer.capacity;
    return total + readback_.byteSize();
}

void GpuCull::run(const CullInputs& inputs, uint32_t arena, std::span<const MeshDrawInfo> meshes) {
    shapeCount_ = inputs.shapeCount;
    CullPages selected = selectCullPages(inputs);
    layout_ = std::move(selected.layout);
    stats_ = {selected.terminals, selected.skippedTerminals, selected.occludedTerminals,
              selected.facingAwayTerminals, selected.billboardTerminals};
    const std::vector<glm::uvec4>& workgroups = selected.pages; // one per page

    std::vector<shared::CullBatch> batches;
    batches.reserve(inputs.batches.size());
    for (const CullBatchInput& input : inputs.batches) {
        shared::CullBatch batch{};
        batch.origin = glm::vec3(input.cellOrigin - inputs.camera);
        batch.shapeBase = input.shapeBase;
        batches.push_back(batch);
    }
    std::vector<glm::uvec4> shapes(shapeCount_), meshInfo(shapeCount_);
    std::vector<glm::vec4> coarse = coarseTable(inputs, layout_);
    coarse.resize(shapeCount_, glm::vec4(0.0f, 0.0f, 0.0f, -1.0f));
    for (uint32_t s = 0; s < shapeCount_; ++s) {
        shapes[s] = glm::uvec4(layout_.base[s], layout_.capacity[s], inputs.shapeImpostor[s],
                               inputs.shapeTree.empty() ? 0u : inputs.shapeTree[s]);
        const MeshDrawInfo& mesh = meshes[s];
        meshInfo[s] = glm::uvec4(mesh.indexCount, mesh.firstIndex, uint32_t(mesh.baseVertex), 0u);
    }
    // The coarse shape of a shape without impostor fills that shape's lists from the back (its
    // z says so); that of a shape with one has lists of its own (DrawListLayout).
    for (uint32_t s = 0; s < coarse.size(); ++s)
        if (coarse[s].w >= 0.0f && shapes.at(s).z == 0u)
            shapes.at(uint32_t(coarse[s].w)).z = HEXLOD_COARSE_SHAPE;

    auto upload = [this](BufferIndex index, const void* data, uint64_t bytes) {
        reserve(index, bytes);
        if (bytes) gl::glNamedBufferSubData(buffers_[index].id, 0, GLsizeiptr(bytes), data);
    };
    upload(kFrame, &inputs.frame, sizeof inputs.frame);
    upload(kBatches, batches.data(), batches.size() * sizeof(shared::CullBatch));
    upload(kWorkgroups, workgroups.data(), workgroups.size() * sizeof(glm::uvec4));
    upload(kShapes, shapes.data(), shapes.size() * sizeof(glm::uvec4));
    upload(kMeshes, meshInfo.data(), meshInfo.size() * sizeof(glm::uvec4));
    upload(kCoarse, coarse.data(), coarse.size() * sizeof(glm::vec4));
    upload(kLod3Bases, layout_.lod3Base.data(), layout_.lod3Base.size() * sizeof(uint32_t));
    reserve(kCounters, uint64_t(shapeCount_) * sizeof(glm::uvec4));
    gl::glClearNamedBufferSubData(buffers_[kCounters].id, GL_R32UI, 0,
                                  GLsizeiptr(shapeCount_ * sizeof(glm::uvec4)), GL_RED_INTEGER,
                                  GL_UNSIGNED_INT, nullptr);
    reserve(kLists, layout_.total * sizeof(gpu::GpuTerminal));
    reserve(kLod3Lists, layout_.lod3Total * sizeof(gpu::GpuTerminal));
    reserve(kCommands, uint64_t(shapeCount_) * 3 * kCommandStride);
    reserve(kOccluded, sizeof(uint32_t));
    gl::glClearNamedBufferSubData(buffers_[kOccluded].id, GL_R32UI, 0, sizeof(uint32_t), GL_RED_INTEGER,
                                  GL_UNSIGNED_INT, nullptr);

    gl::glBindBufferBase(GL_UNIFORM_BUFFER, 0, buffers_[kFrame].id);
    gl::glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, arena);
    for (BufferIndex index : {kBatches, kWorkgroups, kShapes, kCounters, kLists, kMeshes, kCommands,
                              kOccluded, kCoarse, kLod3Lists, kLod3Bases}) {
        gl::glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindings[index], buffers_[index].id);
    }
    if (inputs.treeBuffer) gl::glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 10, inputs.treeBuffer);
    const uint32_t groups = uint32_t(workgroups.size());
    if (groups > 0) {
        cull_.use();
        cull_.set("workgroupCount", groups);
        // Without tiles the frame says so (occlusion.x = 0) and the sampler is never read.
        gl::glBindTextureUnit(kOcclusionUnit, inputs.occlusionTexture);
        cull_.set("occlusionTiles", int(kOcclusionUnit));
        const uint32_t x = std::min<uint32_t>(groups, 65535), y = (groups + x - 1) / x;
        gl::glDispatchCompute(x, y, 1);
        gl::glBindTextureUnit(kOcclusionUnit, 0);
    }
    gl::glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    finalize_.use();
    finalize_.set("shapeCount", shapeCount_);
    gl::glDispatchCompute((shapeCount_ + kWorkgroupSize - 1) / kWorkgroupSize, 1, 1);
    gl::glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT |
                        GL_SHADER_STORAGE_BARRIER_BIT);
}

std::vector<glm::uvec4> GpuCull::readCounters() {
    std::vector<glm::uvec4> counters(shapeCount_);
    readback_.read(buffers_[kCounters].id, 0, counters.size() * sizeof(glm::uvec4), counters.data());
    return counters;
}

uint32_t GpuCull::readOccluded() {
    uint32_t occluded = 0;
    readback_.read(buffers_[kOccluded].id, 0, sizeof occluded, &occluded);
    return occluded;
}

std::vector<gpu::GpuTerminal> GpuCull::readLists() {
    return readRecords(kLists, layout_.total);
}

std::vector<gpu::GpuTerminal> GpuCull::readLod3Lists() {
    return readRecords(kLod3Lists, layout_.lod3Total);
}

std::vector<gpu::GpuTerminal> GpuCull::readRecords(BufferIndex index, uint64_t count) {
    std::vector<gpu::GpuTerminal> records(count);
    readback_.read(buffers_[index].id, 0, records.size() * sizeof(gpu::GpuTerminal), records.data());
    return records;
}

} // namespace hexlod::lod
