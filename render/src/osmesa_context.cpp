// OSMesa, Mesa's off-screen rendering library: the fallback when EGL is missing or refuses.
// OSMesa exports only the GL 1.x entry points; everything newer (DSA, timer queries) comes
// through OSMesaGetProcAddress, which is what gl::loadFunctions is given.
#include "gl_backends.h"

#include <GL/osmesa.h>

#include <vector>

namespace hexlod::render {
namespace {

class OsMesaContext final : public GlContext {
public:
    explicit OsMesaContext(OSMesaContext context) : context_(context), buffer_(4 * 4, 0) {}
    ~OsMesaContext() override { OSMesaDestroyContext(context_); }
    // OSMesa needs a colour buffer to make a context current; every pass draws into framebuffer
    // objects, so a 1x1 one serves.
    bool bind() { return OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, 1, 1); }
    void makeCurrent() override { bind(); }
    GlContextInfo& mutableInfo() { return info_; }

private:
    OSMesaContext context_;
    std::vector<unsigned char> buffer_;
};

} // namespace

std::unique_ptr<GlContext> createOsMesaContext(bool debug, std::string& why) {
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              24,
                              OSMESA_PROFILE,
                              OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION,
                              4,
                              OSMESA_CONTEXT_MINOR_VERSION,
                              5,
                              0};
    OSMesaContext context = OSMesaCreateContextAttribs(attributes, nullptr);
    if (!context) {
        why = "OSMesaCreateContextAttribs for OpenGL 4.5 core failed";
        return nullptr;
    }
    auto result = std::make_unique<OsMesaContext>(context);
    if (!result->bind()) {
        why = "OSMesaMakeCurrent failed";
        return nullptr;
    }
    auto load = [](const char* name) -> void (*)() { return OSMesaGetProcAddress(name); };
    if (!finishContext(GlBackend::OSMesa, debug, load, result->mutableInfo(), why)) return nullptr;
    return result;
}

} // namespace hexlod::render
