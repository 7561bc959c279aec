// The draw passes of a frame, in the order CityRenderer runs them, and their timing with
// CityRendererOptions::timePasses (FrameStats::passMs).
#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>

namespace hexlod::lod {

enum class DrawPass : uint8_t { Lod0, Lod1, Ground, TerminalMeshes, Impostors, Trees, Count };
const char* drawPassName(DrawPass pass); // "terminal_meshes", "impostors", "lod0", ...

using PassTimes = std::array<double, size_t(DrawPass::Count)>; // milliseconds per pass

// When enabled, ends each draw pass with glFinish and adds its time to `times`; otherwise does
// nothing, so an untimed frame never waits between passes.
class PassTimer {
public:
    PassTimer(bool enabled, PassTimes& times);
    void end(DrawPass pass);
    // The next pass starts now: what ran since the last end() (the cull pass, between the
    // occluders and the rest) belongs to no pass.
    void restart();

private:
    bool enabled_;
    PassTimes& times_;
    std::chrono::steady_clock::time_point start_;
};

} // namespace hexlod::lod
