// The GL's own messages (KHR_debug) go to standard error: the commands print their results,
// `walk --json` for one, on standard output, which a driver's warning must not break.
#include "hexlod/render/gl_api.h"
#include "hexlod/render/gl_context.h"
#include "hexlod/render/gl_debug.h"

#include <gtest/gtest.h>

#include <string>

namespace hexlod::render {
namespace {

TEST(GlDebugTest, AGlErrorIsCountedAndLoggedToStandardErrorNotStandardOutput) {
    GlContextResult result = createGlContext();
    ASSERT_TRUE(result.context) << result.error();
    const uint64_t errorsBefore = glDebugErrorCount();
    testing::internal::CaptureStdout();
    testing::internal::CaptureStderr();
    gl::glBindBuffer(GLenum(0x1234), 0); // no such target: GL_INVALID_ENUM
    const GLenum error = gl::glGetError();
    const std::string out = testing::internal::GetCapturedStdout();
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_EQ(error, GLenum(GL_INVALID_ENUM));
    EXPECT_EQ(glDebugErrorCount(), errorsBefore + 1);
    EXPECT_EQ(out, "");
    EXPECT_NE(err.find("GL api"), std::string::npos) << err;
}

} // namespace
} // namespace hexlod::render
