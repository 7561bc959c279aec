#include "hexlod/lod/draw_pass.h"
#include "hexlod/render/gl_api.h"

namespace hexlod::lod {

const char* drawPassName(DrawPass pass) {
    switch (pass) {
    case DrawPass::TerminalMeshes:
        return "terminal_meshes";
    case DrawPass::Lod0:
        return "lod0";
    case DrawPass::Lod1:
        return "lod1";
    case DrawPass::Ground:
        return "ground";
    case DrawPass::Impostors:
        return "impostors";
    case DrawPass::Trees:
    case DrawPass::Count:
        break;
    }
    return "trees";
}

PassTimer::PassTimer(bool enabled, PassTimes& times) : enabled_(enabled), times_(times) {
    if (enabled_) gl::glFinish();
    start_ = std::chrono::steady_clock::now();
}

void PassTimer::restart() {
    if (!enabled_) return;
    gl::glFinish();
    start_ = std::chrono::steady_clock::now();
}

void PassTimer::end(DrawPass pass) {
    if (!enabled_) return;
    gl::glFinish();
    const auto now = std::chrono::steady_clock::now();
    times_[size_t(pass)] += std::chrono::duration<double, std::milli>(now - start_).count();
    start_ = now;
}

} // namespace hexlod::lod
