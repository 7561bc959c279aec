// Off-screen rendering: a triangle drawn into an RGBA16F framebuffer reads back where and
// how it was drawn, colour and depth.
#include "gl_fixture.h"

#include "hexlod/render/framebuffer.h"
#include "hexlod/render/shader_program.h"

namespace hexlod::render {
namespace {

class FramebufferTest : public GlTest {};

// A full-width triangle from attribute-less vertices: covers the lower-left half of the target.
constexpr const char* kVertex = R"(#version 450 core
const vec2 corners[3] = vec2[](vec2(-1, -1), vec2(1, -1), vec2(-1, 1));
void main() { gl_Position = vec4(corners[gl_VertexID], 0.5, 1.0); }
)";
constexpr const char* kFragment = R"(#version 450 core
layout(location = 0) out vec4 color;
layout(location = 1) out vec4 second;
void main() { color = vec4(0.25, 0.5, 1.5, 1.0); second = vec4(-2.0, 0.125, 3.0, 0.5); }
)";

TEST_F(FramebufferTest, ATriangleReadsBackWithItsColourAndDepth) {
    Framebuffer target;
    std::string error;
    ASSERT_TRUE(Framebuffer::create({64, 32, {GL_RGBA16F, GL_RGBA32F}, true}, target, error)) << error;
    ShaderLibrary library;
    library.add("tri.vert", kVertex);
    library.add("tri.frag", kFragment);
    ShaderProgram program = ShaderProgram::build(
        library, {{ShaderStage::Vertex, "tri.vert"}, {ShaderStage::Fragment, "tri.frag"}}, "", error);
    ASSERT_TRUE(program.valid()) << error;
    GLuint vao = 0;
    gl::glCreateVertexArrays(1, &vao);
    target.bind();
    target.clear(0, 0, 0, 0);
    gl::glEnable(GL_DEPTH_TEST);
    program.use();
    gl::glBindVertexArray(vao);
    gl::glDrawArrays(GL_TRIANGLES, 0, 3);
    gl::glDeleteVertexArrays(1, &vao);

    Image color = target.readColor(0), second = target.readColor(1), depth = target.readDepth();
    ASSERT_EQ(color.width, 64u);
    ASSERT_EQ(color.height, 32u);
    // Rows are top first: the bottom-left corner is covered, the top-right is not.
    const float* covered = color.at(2, 29);
    EXPECT_FLOAT_EQ(covered[0], 0.25f);
    EXPECT_FLOAT_EQ(covered[1], 0.5f);
    EXPECT_FLOAT_EQ(covered[2], 1.5f); // RGBA16F keeps values above 1
    EXPECT_FLOAT_EQ(covered[3], 1.0f);
    EXPECT_FLOAT_EQ(color.at(61, 2)[3], 0.0f);
    EXPECT_FLOAT_EQ(second.at(2, 29)[0], -2.0f);
    EXPECT_FLOAT_EQ(second.at(2, 29)[1], 0.125f);
    EXPECT_FLOAT_EQ(depth.at(2, 29)[0], 0.75f); // ndc z 0.5 -> window depth 0.75
    EXPECT_FLOAT_EQ(depth.at(61, 2)[0], 1.0f);
    EXPECT_TRUE(target.readColor(2).empty());
}

TEST_F(FramebufferTest, ZeroAndOversizedExtentsAreRejectedWithAReason) {
    Framebuffer target;
    std::string error;
    EXPECT_FALSE(Framebuffer::create({0, 16}, target, error));
    EXPECT_NE(error.find("extent 0x16"), std::string::npos) << error;
    EXPECT_FALSE(Framebuffer::create({1u << 20, 16}, target, error));
    EXPECT_NE(error.find("outside 1.."), std::string::npos) << error;
    EXPECT_FALSE(Framebuffer::create({16, 16, std::vector<uint32_t>(64, GL_RGBA8)}, target, error));
    EXPECT_NE(error.find("colour attachments"), std::string::npos) << error;
}

TEST_F(FramebufferTest, AMultisampledTargetResolvesEdgesToPartialCoverage) {
    Framebuffer target;
    std::string error;
    ASSERT_TRUE(Framebuffer::create({64, 32, {GL_RGBA16F}, true, 4}, target, error)) << error;
    EXPECT_EQ(target.samples(), 4u);
    ShaderLibrary library;
    library.add("tri.vert", kVertex);
    library.add("tri.frag", kFragment);
    ShaderProgram program = ShaderProgram::build(
        library, {{ShaderStage::Vertex, "tri.vert"}, {ShaderStage::Fragment, "tri.frag"}}, "", error);
    ASSERT_TRUE(program.valid()) << error;
    GLuint vao = 0;
    gl::glCreateVertexArrays(1, &vao);
    target.bind();
    target.clear(0, 0, 0, 0);
    program.use();
    gl::glBindVertexArray(vao);
    gl::glDrawArrays(GL_TRIANGLES, 0, 3);
    gl::glDeleteVertexArrays(1, &vao);
    Image color = target.readColor(0);
    ASSERT_EQ(color.width, 64u);
    EXPECT_FLOAT_EQ(color.at(2, 29)[3], 1.0f); // inside
    EXPECT_FLOAT_EQ(color.at(61, 2)[3], 0.0f); // outside
    // Along the diagonal some pixels are partly covered: that is what multisampling is for.
    int partial = 0;
    for (uint32_t x = 0; x < 64; ++x)
        for (uint32_t y = 0; y < 32; ++y) partial += color.at(x, y)[3] > 0.01f && color.at(x, y)[3] < 0.99f;
    EXPECT_GT(partial, 20);
    EXPECT_TRUE(target.readDepth().empty());
    EXPECT_FALSE(Framebuffer::create({8, 8, {GL_RGBA16F}, true, 1024}, target, error));
    EXPECT_NE(error.find("samples per pixel"), std::string::npos) << error;
}

TEST_F(FramebufferTest, AOneByOneTargetWorks) {
    Framebuffer target;
    std::string error;
    ASSERT_TRUE(Framebuffer::create({1, 1}, target, error)) << error;
    target.clear(0.5f, 0.25f, 0.0f, 1.0f);
    Image color = target.readColor();
    ASSERT_EQ(color.pixels.size(), 4u);
    EXPECT_FLOAT_EQ(color.pixels[0], 0.5f);
    EXPECT_FLOAT_EQ(color.pixels[1], 0.25f);
}

} // namespace
} // namespace hexlod::render
