// Draw pass timing under each clock: nothing timed when off, wall time through glFinish, and
// GL timestamps that give a pass its GPU time where they advance and never a negative one.
#include "../render/gl_fixture.h"

#include "hexlod/lod/draw_pass.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>

namespace hexlod::lod {
namespace {

class PassTimerTest : public render::GlTest {
protected:
    // Some GL work for a pass to hold: a clear of a buffer large enough to take time on a GPU.
    void work() {
        if (!buffer_) {
            gl::glCreateBuffers(1, &buffer_);
            gl::glNamedBufferStorage(buffer_, 64 << 20, nullptr, 0);
        }
        gl::glClearNamedBufferSubData(buffer_, GL_R32UI, 0, 64 << 20, GL_RED_INTEGER, GL_UNSIGNED_INT,
                                      nullptr);
    }
    void TearDown() override {
        if (buffer_) gl::glDeleteBuffers(1, &buffer_);
        render::GlTest::TearDown();
    }
    GLuint buffer_ = 0;
};

TEST_F(PassTimerTest, OffTimesNothing) {
    PassTimes times{};
    PassTimer timer(PassClock::Off, times);
    work();
    timer.end(DrawPass::Lod0);
    timer.collect();
    for (double ms : times) EXPECT_EQ(ms, 0.0);
}

TEST_F(PassTimerTest, FinishAndWallGivesEachPassTheTimeBetweenItsEnds) {
    PassTimes times{};
    {
        PassTimer timer(PassClock::FinishAndWall, times);
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        timer.end(DrawPass::Lod0);
        work();
        timer.end(DrawPass::Trees);
        // What runs between a restart and the last end belongs to no pass.
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        timer.restart();
        timer.end(DrawPass::Lod1);
        timer.collect();
    }
    EXPECT_GE(times[size_t(DrawPass::Lod0)], 20.0);
    EXPECT_GT(times[size_t(DrawPass::Trees)], 0.0);
    EXPECT_LT(times[size_t(DrawPass::Lod1)], 20.0);
    EXPECT_EQ(times[size_t(DrawPass::Impostors)], 0.0);
}

TEST_F(PassTimerTest, GpuTimestampsGiveAPassItsGpuTimeOnlyOnceCollected) {
    PassTimes times{};
    {
        PassTimer timer(PassClock::GpuTimestamps, times);
        work();
        timer.end(DrawPass::TerminalMeshes);
        // The CPU's time between passes is not the GPU's.
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        timer.restart();
        timer.end(DrawPass::Impostors);
        for (double ms : times) EXPECT_EQ(ms, 0.0) << "nothing is read before collect()";
        gl::glFinish();
        timer.collect();
    }
    for (double ms : times) EXPECT_GE(ms, 0.0);
    EXPECT_LT(times[size_t(DrawPass::Impostors)], 20.0);
    // Only a GPU's timestamps say what the pass cost (GlContextInfo::gpuTimestamps); llvmpipe
    // stamps commands as they are queued, so its passes read near 0 here.
    if (context().info().gpuTimestamps()) {
        EXPECT_GT(times[size_t(DrawPass::TerminalMeshes)], 0.0);
    }
    EXPECT_EQ(times[size_t(DrawPass::Lod0)], 0.0);
}

TEST(PassClockTest, NamesSayHowPassesAreTimed) {
    EXPECT_EQ(std::string(passClockName(PassClock::Off)), "off");
    EXPECT_EQ(std::string(passClockName(PassClock::FinishAndWall)), "finish-and-wall");
    EXPECT_EQ(std::string(passClockName(PassClock::GpuTimestamps)), "gpu-timestamps");
}

} // namespace
} // namespace hexlod::lod
