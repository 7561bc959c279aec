#include "hexlod/lod/depth_tiles.h"
#include "hexlod/lod/gpu_cull.h"
#include "hexlod/render/gl_api.h"

#include <algorithm>

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

bool DepthTiles::init(uint32_t width, uint32_t height, uint32_t samples, uint32_t tileSize,
                      std::string& error) {
    if (tileSize == 0) {
        error = "depth tiles: the tile size must be at least one pixel";
        return false;
    }
    samples_ = samples;
    tileSize_ = tileSize;
    columns_ = (width + tileSize - 1) / tileSize;
    rows_ = (height + tileSize - 1) / tileSize;
    const auto tilesAt = [&](uint32_t level) {
        const uint32_t size = 1u << level;
        return uint64_t((columns_ + size - 1) / size) * ((rows_ + size - 1) / size);
    };
    levels_ = 1;
    while (tilesAt(levels_ - 1) > kDepthTileLookups) ++levels_;
    const uint32_t align = 1u << (levels_ - 1);
    paddedColumns_ = (columns_ + align - 1) / align * align;
    paddedRows_ = (rows_ + align - 1) / align * align;
    render::ShaderLibrary library = lodShaderLibrary();
    program_ = render::ShaderProgram::build(library, {{render::ShaderStage::Compute, "depth_tiles.comp"}},
                                            samples > 1 ? "#define MULTISAMPLED 1\n" : "", error);
    if (!program_.valid()) return false;
    reduceProgram_ = render::ShaderProgram::build(
        library, {{render::ShaderStage::Compute, "depth_tiles_reduce.comp"}}, "", error);
    if (!reduceProgram_.valid()) return false;
    gl::glCreateTextures(GL_TEXTURE_2D, 1, &texture_);
    gl::glTextureStorage2D(texture_, GLsizei(levels_), GL_R32F, GLsizei(paddedColumns_),
                           GLsizei(paddedRows_));
    // texelFetch reads any level only with a mipmap filter.
    gl::glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    gl::glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
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
    const std::vector<float> padded = readLevel(0);
    std::vector<float> tiles;
    tiles.reserve(size_t(columns_) * rows_);
    for (uint32_t row = 0; row < rows_; ++row) {
        const auto first = padded.begin() + ptrdiff_t(row) * paddedColumns_;
        tiles.insert(tiles.end(), first, first + columns_);
    }
    return tiles;
}

std::vector<float> DepthTiles::readLevel(uint32_t level) const {
    std::vector<float> tiles(size_t(paddedColumns_ >> level) * (paddedRows_ >> level));
    gl::glGetTextureImage(texture_, GLint(level), GL_RED, GL_FLOAT, GLsizei(tiles.size() * sizeof(float)),
                          tiles.data());
    return tiles;
}

uint64_t DepthTiles::byteSize() const {
    uint64_t bytes = readback_.byteSize();
    for (uint32_t level = 0; level < levels_; ++level)
        bytes += uint64_t(paddedColumns_ >> level) * (paddedRows_ >> level) * sizeof(float);
    return bytes;
}

void DepthTiles::build(uint32_t depthTexture, bool coarserLevels) {
    program_.use();
    // The gather's 2 x 2 footprint may reach past the target's last row or column.
    if (samples_ <= 1) {
        gl::glTextureParameteri(depthTexture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        gl::glTextureParameteri(depthTexture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    gl::glBindTextureUnit(0, depthTexture);
    program_.set("depthTarget", 0);
    program_.set("tileSize", tileSize_);
    // A thread reduces about kDepthTileSize pixels each way, whatever the tile size.
    const uint32_t across = std::max(1u, kDepthTileSize / tileSize_);
    program_.set("tilesAcross", across);
    program_.set("samples", samples_);
    gl::glBindImageTexture(0, texture_, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    const auto dispatch = [](uint32_t columns, uint32_t rows) {
        gl::glDispatchCompute((columns + kLocalSize - 1) / kLocalSize, (rows + kLocalSize - 1) / kLocalSize,
                              1);
    };
    dispatch((paddedColumns_ + across - 1) / across, (paddedRows_ + across - 1) / across);
    builtLevels_ = coarserLevels ? levels_ : 1;
    if (builtLevels_ > 1) {
        reduceProgram_.use();
        for (uint32_t level = 1; level < builtLevels_; ++level) {
            gl::glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            gl::glBindImageTexture(0, texture_, GLint(level - 1), GL_FALSE, 0, GL_READ_ONLY, GL_R32F);
            gl::glBindImageTexture(1, texture_, GLint(level), GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
            dispatch(paddedColumns_ >> level, paddedRows_ >> level);
        }
    }
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
    program.set("depthTileSize", tileSize_);
    program.set("depthTileLevels", builtLevels_);
    program.set("depthTileLookups", kDepthTileLookups);
    program.set("depthTilesEnabled", uint32_t(enabled));
}

} // namespace hexlod::lod
