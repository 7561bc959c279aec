// A test fixture that owns an OpenGL 4.5 core context on llvmpipe (EGL surfaceless, or
// whatever HEXLOD_GL_BACKEND names) and checks that a test raised no GL error.
#pragma once

#include "hexlod/render/gl_api.h"
#include "hexlod/render/gl_context.h"
#include "hexlod/render/gl_debug.h"

#include <gtest/gtest.h>

#include <memory>

namespace hexlod::render {

class GlTest : public ::testing::Test {
protected:
    void SetUp() override {
        GlContextResult result = createGlContext();
        ASSERT_TRUE(result.context) << result.error();
        context_ = std::move(result.context);
        errorsBefore_ = glDebugErrorCount();
    }
    void TearDown() override {
        if (!context_) return;
        EXPECT_EQ(gl::glGetError(), GLenum(GL_NO_ERROR));
        EXPECT_EQ(glDebugErrorCount(), errorsBefore_) << "GL debug output reported errors";
    }
    GlContext& context() { return *context_; }

private:
    std::unique_ptr<GlContext> context_;
    uint64_t errorsBefore_ = 0;
};

} // namespace hexlod::render
