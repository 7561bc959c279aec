// Context creation on every backend this machine has: EGL surfaceless and OSMesa run on
// llvmpipe in CI; the EGL device platform needs a GPU and is exercised only where one exists.
#include "hexlod/render/gl_api.h"
#include "hexlod/render/gl_context.h"
#include "hexlod/render/gl_debug.h"

#include <gtest/gtest.h>

#include <cstdlib>

namespace hexlod::render {
namespace {

void expectWorkingContext(const GlContextResult& result, GlBackend backend) {
    ASSERT_TRUE(result.context) << result.error();
    const GlContextInfo& info = result.context->info();
    EXPECT_EQ(info.backend, backend);
    EXPECT_NE(info.version.find("4.5"), std::string::npos) << info.version;
    EXPECT_FALSE(info.renderer.empty());
    GLint profile = 0;
    gl::glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
    EXPECT_EQ(gl::glGetError(), GLenum(GL_NO_ERROR));
}

TEST(GlContextTest, EglSurfacelessGivesA45CoreContext) {
    GlContextResult result = createGlContext({GlBackend::EglSurfaceless});
    expectWorkingContext(result, GlBackend::EglSurfaceless);
}

TEST(GlContextTest, OsMesaGivesA45CoreContextWithDsaFunctions) {
    GlContextResult result = createGlContext({GlBackend::OSMesa});
    expectWorkingContext(result, GlBackend::OSMesa);
    // DSA entry points are the ones libOSMesa does not export; they must have been loaded.
    GLuint buffer = 0;
    gl::glCreateBuffers(1, &buffer);
    EXPECT_NE(buffer, 0u);
    gl::glDeleteBuffers(1, &buffer);
}

TEST(GlContextTest, AutoPicksAWorkingBackendWithNoEnvironment) {
    unsetenv("HEXLOD_GL_BACKEND");
    GlContextResult result = createGlContext();
    ASSERT_TRUE(result.context) << result.error();
    EXPECT_NE(result.context->info().backend, GlBackend::Auto);
}

TEST(GlContextTest, EnvironmentChoosesTheBackendUnderAuto) {
    setenv("HEXLOD_GL_BACKEND", "osmesa", 1);
    GlContextResult result = createGlContext();
    unsetenv("HEXLOD_GL_BACKEND");
    expectWorkingContext(result, GlBackend::OSMesa);
}

TEST(GlContextTest, AnUnknownEnvironmentBackendIsAnErrorThatNamesIt) {
    setenv("HEXLOD_GL_BACKEND", "vulkan", 1);
    GlContextResult result = createGlContext();
    unsetenv("HEXLOD_GL_BACKEND");
    EXPECT_FALSE(result.context);
    EXPECT_NE(result.error().find("HEXLOD_GL_BACKEND=vulkan: unknown backend"), std::string::npos)
        << result.error();
}

TEST(GlContextTest, AFailedBackendSaysWhy) {
    // Without a GPU the device platform has at most Mesa's software device, which an explicit
    // request accepts; either way the outcome is a context or a reason naming the backend.
    GlContextResult result = createGlContext({GlBackend::EglDevice});
    if (!result.context) {
        ASSERT_EQ(result.attempts.size(), 1u);
        EXPECT_EQ(result.attempts[0].rfind("egl-device: ", 0), 0u) << result.attempts[0];
    } else {
        expectWorkingContext(result, GlBackend::EglDevice);
    }
}

TEST(GlContextTest, BackendNamesRoundTrip) {
    for (GlBackend backend :
         {GlBackend::Auto, GlBackend::EglDevice, GlBackend::EglSurfaceless, GlBackend::OSMesa}) {
        GlBackend parsed = GlBackend::Auto;
        ASSERT_TRUE(parseGlBackend(glBackendName(backend), parsed));
        EXPECT_EQ(parsed, backend);
    }
    GlBackend parsed = GlBackend::OSMesa;
    EXPECT_FALSE(parseGlBackend("EGL", parsed));
    EXPECT_EQ(parsed, GlBackend::OSMesa);
}

} // namespace
} // namespace hexlod::render
