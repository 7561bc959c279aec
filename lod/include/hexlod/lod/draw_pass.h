// The draw passes of a frame, in the order CityRenderer runs them, and their timing with
// CityRendererOptions::passClock (FrameStats::passMs).
#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace hexlod::lod {

enum class DrawPass : uint8_t { Lod0, Lod1, Ground, TerminalMeshes, Impostors, Trees, Count };
const char* drawPassName(DrawPass pass); // "terminal_meshes", "impostors", "lod0", ...

using PassTimes = std::array<double, size_t(DrawPass::Count)>; // milliseconds per pass

// How a frame's draw passes are timed.
enum class PassClock : uint8_t {
    Off,           // not at all: no pass waits for the GL
    FinishAndWall, // each pass ends with glFinish and is timed by the wall clock (any GL)
    GpuTimestamps, // GL timestamps around each pass, read once the frame is done (a GPU)
};
const char* passClockName(PassClock clock); // "off", "finish-and-wall", "gpu-timestamps"

// Adds each draw pass's time to `times`. With GpuTimestamps the passes run unhindered and
// collect() reads the times once the frame has finished; with FinishAndWall every pass waits
// for the GL, which costs a tiled rasteriser (llvmpipe) its overlap between passes but is
// all a GL whose timestamps do not advance can offer.
class PassTimer {
public:
    PassTimer(PassClock clock, PassTimes& times);
    ~PassTimer();
    PassTimer(const PassTimer&) = delete;
    PassTimer& operator=(const PassTimer&) = delete;

    void end(DrawPass pass);
    // The next pass starts now: what ran since the last end() (the cull pass, between the
    // occluders and the rest) belongs to no pass.
    void restart();
    // GpuTimestamps: adds the passes' times; call once the frame's commands have finished.
    void collect();

private:
    uint32_t stamp(); // a GL timestamp query issued now

    struct Span {
        DrawPass pass;
        uint32_t start, end; // queries
    };
    PassClock clock_;
    PassTimes& times_;
    std::chrono::steady_clock::time_point start_;
    uint32_t startQuery_ = 0;
    std::vector<uint32_t> queries_;
    std::vector<Span> spans_;
};

} // namespace hexlod::lod
