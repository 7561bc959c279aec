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

const char* passClockName(PassClock clock) {
    switch (clock) {
    case PassClock::FinishAndWall:
        return "finish-and-wall";
    case PassClock::GpuTimestamps:
        return "gpu-timestamps";
    case PassClock::Off:
        break;
    }
    return "off";
}

PassTimer::PassTimer(PassClock clock, PassTimes& times) : clock_(clock), times_(times) {
    restart();
}

PassTimer::~PassTimer() {
    if (!queries_.empty()) gl::glDeleteQueries(GLsizei(queries_.size()), queries_.data());
}

uint32_t PassTimer::stamp() {
    GLuint query = 0;
    gl::glCreateQueries(GL_TIMESTAMP, 1, &query);
    gl::glQueryCounter(query, GL_TIMESTAMP);
    queries_.push_back(query);
    return query;
}

void PassTimer::restart() {
    if (clock_ == PassClock::GpuTimestamps) startQuery_ = stamp();
    if (clock_ != PassClock::FinishAndWall) return;
    gl::glFinish();
    start_ = std::chrono::steady_clock::now();
}

void PassTimer::end(DrawPass pass) {
    if (clock_ == PassClock::GpuTimestamps) {
        const uint32_t end = stamp();
        spans_.push_back({pass, startQuery_, end});
        startQuery_ = end;
    }
    if (clock_ != PassClock::FinishAndWall) return;
    gl::glFinish();
    const auto now = std::chrono::steady_clock::now();
    times_[size_t(pass)] += std::chrono::duration<double, std::milli>(now - start_).count();
    start_ = now;
}

void PassTimer::collect() {
    for (const Span& span : spans_) {
        GLuint64 start = 0, end = 0;
        gl::glGetQueryObjectui64v(span.start, GL_QUERY_RESULT, &start);
        gl::glGetQueryObjectui64v(span.end, GL_QUERY_RESULT, &end);
        // Nanoseconds; a GL whose timestamps do not advance gives 0, never a negative time.
        if (end > start) times_[size_t(span.pass)] += double(end - start) / 1e6;
    }
    spans_.clear();
}

} // namespace hexlod::lod
