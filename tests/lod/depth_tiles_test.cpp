// The depth tiles' levels: each coarser tile holds the farthest depth of the tiles under it (of
// every sample where the target is multisampled), and the vertex-stage test (depth_tiles.glsl)
// drops a rectangle over the whole screen when the tiles hide it, which at one level it could
// not afford to look up.
#include "../render/gl_fixture.h"

#include "hexlod/lod/depth_tiles.h"
#include "hexlod/lod/gpu_cull.h"
#include "hexlod/render/framebuffer.h"
#include "hexlod/render/gl_api.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

namespace hexlod::lod {
namespace {

class DepthTilesTest : public render::GlTest {
protected:
    void TearDown() override {
        if (depth_) gl::glDeleteTextures(1, &depth_);
        render::GlTest::TearDown();
    }
    // A depth texture of `width` x `height` holding `depths` (row by row from the bottom).
    uint32_t depthTexture(uint32_t width, uint32_t height, const std::vector<float>& depths) {
        if (depth_) gl::glDeleteTextures(1, &depth_);
        gl::glCreateTextures(GL_TEXTURE_2D, 1, &depth_);
        gl::glTextureStorage2D(depth_, 1, GL_DEPTH_COMPONENT32F, GLsizei(width), GLsizei(height));
        gl::glTextureSubImage2D(depth_, 0, 0, 0, GLsizei(width), GLsizei(height), GL_DEPTH_COMPONENT,
                                GL_FLOAT, depths.data());
        return depth_;
    }
    uint32_t depth_ = 0;
};

// The tiles of one level from the level below it, on the CPU: a tile past the finer grid
// holds 1 (the nearest depth), as DepthTiles pads it.
std::vector<float> coarser(const std::vector<float>& finer, uint32_t columns, uint32_t rows) {
    std::vector<float> out(size_t(columns / 2) * (rows / 2));
    for (uint32_t y = 0; y < rows / 2; ++y)
        for (uint32_t x = 0; x < columns / 2; ++x)
            out[y * (columns / 2) + x] =
                std::min({finer[2 * y * columns + 2 * x], finer[2 * y * columns + 2 * x + 1],
                          finer[(2 * y + 1) * columns + 2 * x], finer[(2 * y + 1) * columns + 2 * x + 1]});
    return out;
}

// Every level of `tiles`, built over a width x height target whose pixels' farthest depths are
// `farthest` (row by row from the bottom), against the CPU's reduction; and the copy read back.
void expectLevels(DepthTiles& tiles, const std::vector<float>& farthest, uint32_t width, uint32_t height,
                  const std::string& what) {
    const uint32_t tileSize = tiles.tileSize();
    // Enough levels that the coarsest covers the target in kDepthTileLookups tiles.
    const uint32_t coarsest = tiles.levels() - 1;
    const uint32_t step = 1u << coarsest;
    EXPECT_LE(((tiles.columns() + step - 1) / step) * ((tiles.rows() + step - 1) / step), kDepthTileLookups)
        << what;
    EXPECT_EQ(tiles.paddedColumns() % step, 0u) << what;
    EXPECT_EQ(tiles.paddedRows() % step, 0u) << what;

    // Level 0: the farthest depth of each tile's pixels; 1 past the target.
    std::vector<float> expected(size_t(tiles.paddedColumns()) * tiles.paddedRows(), 1.0f);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            float& tile = expected[(y / tileSize) * tiles.paddedColumns() + x / tileSize];
            tile = std::min(tile, farthest[size_t(y) * width + x]);
        }
    uint32_t columns = tiles.paddedColumns(), rows = tiles.paddedRows();
    for (uint32_t level = 0; level < tiles.levels(); ++level) {
        EXPECT_EQ(tiles.readLevel(level), expected) << what << ", level " << level;
        expected = coarser(expected, columns, rows);
        columns /= 2;
        rows /= 2;
    }
    // The copy the CPU tests read: level 0 without the padding.
    const std::vector<float> unpadded = tiles.read();
    ASSERT_EQ(unpadded.size(), size_t(tiles.columns()) * tiles.rows()) << what;
    const std::vector<float> level0 = tiles.readLevel(0);
    for (uint32_t y = 0; y < tiles.rows(); ++y)
        for (uint32_t x = 0; x < tiles.columns(); ++x)
            EXPECT_EQ(unpadded[y * tiles.columns() + x], level0[y * tiles.paddedColumns() + x]) << what;
}

TEST_F(DepthTilesTest, EveryCoarserTileHoldsTheFarthestDepthOfTheTilesUnderIt) {
    // Sizes whose tiles do not halve evenly, so the grid is padded; the cull's tiles and the
    // base volume rings' finer ones.
    for (const uint32_t tileSize : {kDepthTileSize, kVolumeTileSize})
        for (const auto& [width, height] :
             {std::pair{300u, 170u}, std::pair{1280u, 720u}, std::pair{16u, 16u}, std::pair{3u, 5u}}) {
            std::mt19937 random(width);
            std::uniform_real_distribution<float> depth(0.0f, 1.0f);
            std::vector<float> depths(size_t(width) * height);
            for (float& d : depths) d = depth(random);
            DepthTiles tiles;
            std::string error;
            ASSERT_TRUE(tiles.init(width, height, 1, tileSize, error)) << error;
            EXPECT_EQ(tiles.tileSize(), tileSize);
            tiles.build(depthTexture(width, height, depths), true);
            expectLevels(tiles, depths, width, height,
                         std::to_string(width) + " x " + std::to_string(height) + " in tiles of " +
                             std::to_string(tileSize));
        }
}

// A multisampled target is reduced over every sample of every pixel: each sample of each pixel
// gets its own depth (the fragment shader reads gl_SampleID, so it runs per sample).
TEST_F(DepthTilesTest, AMultisampledTargetIsReducedOverEverySample) {
    constexpr uint32_t kSamples = 4;
    std::string error;
    if (!render::unsupportedSamples(kSamples).empty()) GTEST_SKIP() << render::unsupportedSamples(kSamples);
    render::ShaderLibrary library = lodShaderLibrary();
    library.add("fill.vert", "#version 450 core\n"
                             "void main() {\n"
                             "    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);\n"
                             "    gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);\n"
                             "}\n");
    // Depths exact in float: the CPU computes the same.
    library.add("fill.frag",
                "#version 450 core\n"
                "void main() {\n"
                "    ivec2 p = ivec2(gl_FragCoord.xy);\n"
                "    gl_FragDepth = float((p.x * 7 + p.y * 13 + gl_SampleID * 29) % 97) / 128.0;\n"
                "}\n");
    const render::ShaderProgram fill = render::ShaderProgram::build(
        library, {{render::ShaderStage::Vertex, "fill.vert"}, {render::ShaderStage::Fragment, "fill.frag"}},
        "", error);
    ASSERT_TRUE(fill.valid()) << error;
    uint32_t vao = 0;
    gl::glCreateVertexArrays(1, &vao);
    for (const uint32_t tileSize : {kDepthTileSize, kVolumeTileSize})
        for (const auto& [width, height] : {std::pair{300u, 170u}, std::pair{64u, 48u}}) {
            render::Framebuffer target;
            ASSERT_TRUE(
                render::Framebuffer::create({width, height, {GL_RGBA8}, true, kSamples}, target, error))
                << error;
            target.bind();
            target.clear(0.0f, 0.0f, 0.0f, 1.0f, 1.0f);
            gl::glEnable(GL_DEPTH_TEST);
            gl::glDepthFunc(GL_ALWAYS);
            gl::glDepthMask(GL_TRUE);
            fill.use();
            gl::glBindVertexArray(vao);
            gl::glDrawArrays(GL_TRIANGLES, 0, 3);
            gl::glBindVertexArray(0);
            gl::glDepthFunc(GL_LESS);
            gl::glDisable(GL_DEPTH_TEST);
            std::vector<float> farthest(size_t(width) * height, 1.0f);
            for (uint32_t y = 0; y < height; ++y)
                for (uint32_t x = 0; x < width; ++x)
                    for (uint32_t s = 0; s < kSamples; ++s)
                        farthest[size_t(y) * width + x] = std::min(
                            farthest[size_t(y) * width + x], float((x * 7 + y * 13 + s * 29) % 97) / 128.0f);
            DepthTiles tiles;
            ASSERT_TRUE(tiles.init(width, height, kSamples, tileSize, error)) << error;
            tiles.build(target.depthTexture(), true);
            expectLevels(tiles, farthest, width, height,
                         std::to_string(width) + " x " + std::to_string(height) + " at " +
                             std::to_string(kSamples) + " samples in tiles of " + std::to_string(tileSize));
        }
    gl::glDeleteVertexArrays(1, &vao);
}

// Runs behindDepthTiles once per rectangle in a vertex shader (no rasterisation).
constexpr const char* kProbe = R"(#version 450 core
#include "frame.glsl"
#include "depth_tiles.glsl"
layout(std430, binding = 2) readonly buffer Rectangles { vec4 rectangles[]; }; // ndc lo, hi
layout(std430, binding = 3) readonly buffer Nearest { float nearest[]; };
layout(std430, binding = 4) writeonly buffer Hidden { uint hidden[]; };
void main() {
    vec4 r = rectangles[gl_VertexID];
    hidden[gl_VertexID] = uint(behindDepthTiles(r.xy, r.zw, nearest[gl_VertexID]));
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
)";

TEST_F(DepthTilesTest, AScreenWideRectangleIsDroppedWhereTheTilesHideItAndKeptWhereOneMayShowIt) {
    // A wall at depth 0.5 over a 1280 x 720 target (3,600 tiles), but for one hole of
    // 32 x 32 pixels at depth 0 (the sky, reversed-Z) in its upper right.
    constexpr uint32_t width = 1280, height = 720;
    std::vector<float> depths(size_t(width) * height, 0.5f);
    for (uint32_t y = 600; y < 632; ++y)
        for (uint32_t x = 1000; x < 1032; ++x) depths[size_t(y) * width + x] = 0.0f;
    DepthTiles tiles;
    std::string error;
    ASSERT_TRUE(tiles.init(width, height, 1, kDepthTileSize, error)) << error;
    ASSERT_GT(tiles.levels(), 1u);
    const uint32_t depth = depthTexture(width, height, depths);

    render::ShaderLibrary library = lodShaderLibrary();
    library.add("probe.vert", kProbe);
    library.add("probe.frag", "#version 450 core\nvoid main() {}\n");
    const render::ShaderProgram probe = render::ShaderProgram::build(
        library, {{render::ShaderStage::Vertex, "probe.vert"}, {render::ShaderStage::Fragment, "probe.frag"}},
        "", error);
    ASSERT_TRUE(probe.valid()) << error;

    struct Case {
        const char* what;
        glm::vec4 rectangle; // ndc lo, hi
        float nearest;
        bool hidden;
    };
    // The hole in ndc: x from 1000 / 640 - 1, y from 600 / 360 - 1.
    const float holeX = 1000.0f / 640.0f - 1.0f, holeY = 600.0f / 360.0f - 1.0f;
    const Case cases[] = {
        {"the whole screen behind the wall", {-1, -1, 1, 1}, 0.4f, false}, // the hole shows it
        // A quarter of the screen (900 tiles) away from the hole, tested on 128-pixel tiles.
        {"the lower left quarter, behind the wall", {-1, -1, 0, 0}, 0.4f, true},
        {"the lower left quarter, before the wall", {-1, -1, 0, 0}, 0.6f, false},
        {"a wide rectangle over the hole, behind the wall", {0.0f, 0.0f, 1, 1}, 0.4f, false},
        {"a small rectangle in the hole",
         {holeX + 0.01f, holeY + 0.01f, holeX + 0.02f, holeY + 0.02f},
         0.1f,
         false},
        {"a small rectangle behind the wall", {-0.5f, -0.5f, -0.45f, -0.45f}, 0.4f, true},
    };
    constexpr size_t kQuarterBehind = 1;
    std::vector<glm::vec4> rectangles;
    std::vector<float> nearest;
    for (const Case& c : cases) {
        rectangles.push_back(c.rectangle);
        nearest.push_back(c.nearest);
    }
    // The frame block: only the viewport matters here.
    std::vector<float> frame(16 + 4 * 4, 0.0f);
    frame[16 + 12] = float(width), frame[16 + 13] = float(height);
    uint32_t buffers[4];
    gl::glCreateBuffers(4, buffers);
    gl::glNamedBufferStorage(buffers[0], GLsizeiptr(frame.size() * sizeof(float)), frame.data(), 0);
    gl::glNamedBufferStorage(buffers[1], GLsizeiptr(rectangles.size() * sizeof(glm::vec4)), rectangles.data(),
                             0);
    gl::glNamedBufferStorage(buffers[2], GLsizeiptr(nearest.size() * sizeof(float)), nearest.data(), 0);
    gl::glNamedBufferStorage(buffers[3], GLsizeiptr(nearest.size() * sizeof(uint32_t)), nullptr,
                             GL_DYNAMIC_STORAGE_BIT);
    gl::glBindBufferBase(GL_UNIFORM_BUFFER, 1, buffers[0]);
    for (uint32_t i = 1; i < 4; ++i) gl::glBindBufferBase(GL_SHADER_STORAGE_BUFFER, i + 1, buffers[i]);
    // A draw needs a target, even one that rasterises nothing.
    render::Framebuffer target;
    ASSERT_TRUE(render::Framebuffer::create({1, 1, {GL_RGBA8}, false, 1}, target, error)) << error;
    uint32_t vao = 0;
    gl::glCreateVertexArrays(1, &vao);
    // Which rectangles the vertex-stage test finds hidden, against the tiles as built last.
    const auto probeHidden = [&] {
        target.bind();
        probe.use();
        tiles.bind(probe, 0, TileTest::Lod3Impostors, true);
        gl::glBindVertexArray(vao);
        gl::glEnable(GL_RASTERIZER_DISCARD);
        gl::glDrawArrays(GL_POINTS, 0, GLsizei(nearest.size()));
        gl::glDisable(GL_RASTERIZER_DISCARD);
        gl::glBindVertexArray(0);
        gl::glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        std::vector<uint32_t> hidden(nearest.size());
        gl::glGetNamedBufferSubData(buffers[3], 0, GLsizeiptr(hidden.size() * sizeof(uint32_t)),
                                    hidden.data());
        return hidden;
    };

    tiles.build(depth, true);
    const std::vector<uint32_t> withLevels = probeHidden();
    for (size_t i = 0; i < withLevels.size(); ++i)
        EXPECT_EQ(withLevels[i] != 0, cases[i].hidden) << cases[i].what;
    // Built for the cull pass alone, the tiles have no coarser levels to test on: the quarter
    // is too large to look up and counts as visible; the rest is decided as before.
    tiles.build(depth, false);
    const std::vector<uint32_t> finestOnly = probeHidden();
    for (size_t i = 0; i < finestOnly.size(); ++i)
        EXPECT_EQ(finestOnly[i] != 0, cases[i].hidden && i != kQuarterBehind)
            << cases[i].what << ", finest only";
    gl::glDeleteVertexArrays(1, &vao);
    gl::glDeleteBuffers(4, buffers);
}

TEST_F(DepthTilesTest, TilesOfNoPixelsAreAnError) {
    DepthTiles tiles;
    std::string error;
    EXPECT_FALSE(tiles.init(64, 64, 1, 0, error));
    EXPECT_NE(error.find("tile size"), std::string::npos) << error;
    EXPECT_FALSE(tiles.valid());
}

} // namespace
} // namespace hexlod::lod
