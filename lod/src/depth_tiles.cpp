#include "hexlod/lod/depth_tiles.h"
#include "hexlod/lod/gpu_cull.h"
#include "hexlod/render/gl_api.h"

namespace hexlod::lod {
namespace {

constexpr uint32_t kLocalSize = 8; // depth_tiles.comp's local size, each way
constexpr GLsizeiptr kCountBytes = GLsizeiptr(uint32_t(TileTest::Count) * sizeof(uint32_t));
constexpr uint32_t kCountBinding = 14; // depth_tiles.glsl's DroppedBuffer

} // namespace

DepthTiles::~DepthTiles() {
    if (texture_) gl::glDeleteTextures(1, &texture_);
    if (counts_) gl::glDeleteBuffers(1, &counts_);
}

bool DepthTiles::init(uint32_t width, uint32_t height, uint32_t samples, std::string& error) {
    samples_ = samples;
    columns_ = (width + kDepthTileSize - 1) / kDepthTileSize;
    rows_ = (height + kDepthTileSize - 1) / kDepthTileSize;
    render::ShaderLibrary library = lodShaderLibrary();
    program_ = render::ShaderProgram::build(library, {{render::ShaderStage::Compute, "depth_tiles.comp"}},
                                            samples > 1 ? "#define MULTISAMPLED 1\n" : "", error);
    if (!program_.valid()) return false;
    gl::glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
    gl::glTextureStorage2D(texture_, 1, GL_R32F, GLsizei(columns_), GLsizei(rows_));
    gl::glCreateBuffers(1, &counts_);
    gl::glNamedBufferStorage(counts_, kCountBytes, nullptr, GL_DYNAMIC_STORAGE_BIT);
    return true;
}

void DepthTiles::clearCounts() const {
    gl::glClearNamedBufferSubData(counts_, GL_R32UI, 0, kCountBytes, GL_RED_INTEGER, GL_UNSIGNED_INT,
                                  nullptr);
}

std::array<uint32_t, size_t(TileTest::Count)> DepthTiles::dropped() {
    std::array<uint32_t, size_t(TileTest::Count)> counts{};
    readback_.read(counts_, 0, kCountBytes, counts.data());
    return counts;
}

std::vector<float> DepthTiles::read() const {
    std::vector<float> tiles(size_t(columns_) * rows_);
    gl::glGetTextureImage(texture_, 0, GL_RED, GL_FLOAT, GLsizei(tiles.size() * sizeof(float)), tiles.data());
    return tiles;
}

void DepthTiles::build(uint32_t depthTexture) const {
    program_.use();
    gl::glBindTextureUnit(0, depthTexture);
    program_.set("depthTarget", 0);
    program_.set("tileSize", kDepthTileSize);
    program_.set("samples", samples_);
    gl::glBindImageTexture(0, texture_, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    gl::glDispatchCompute((columns_ + kLocalSize - 1) / kLocalSize, (rows_ + kLocalSize - 1) / kLocalSize, 1);
    gl::glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    // The depth texture stays attached to the target being drawn: left bound, any later
    // program sampling unit 0 would read it while writing it.
    gl::glBindTextureUnit(0, 0);
}

void DepthTiles::bind(const render::ShaderProgram& program, uint32_t unit, TileTest test,
                      bool enabled) const {
    gl::glBindTextureUnit(unit, texture_);
    gl::glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCountBinding, counts_);
    program.set("depthTileCount", uint32_t(test));
    program.set("depthTiles", int(unit));
    program.set("depthTileSize", kDepthTileSize);
    program.set("depthTilesEnabled", uint32_t(enabled));
}

} // namespace hexlod::lod
