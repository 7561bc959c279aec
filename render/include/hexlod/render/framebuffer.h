// An off-screen render target: colour attachments (RGBA16F by default) and a 32-bit float
// depth attachment, all textures so later passes can sample them. Owns its GL objects.
#pragma once

#include "hexlod/render/image.h"

#include <cstdint>
#include <string>
#include <vector>

namespace hexlod::render {

struct FramebufferDesc {
    uint32_t width = 0, height = 0;
    std::vector<uint32_t> colorFormats{0x881A}; // GL internal formats; default GL_RGBA16F
    bool depth = true;                          // GL_DEPTH_COMPONENT32F
    uint32_t samples = 1;                       // above 1: multisampled, resolved on readback
};

// Empty when this GL can multisample a target `samples` times (1: not at all), else why not.
// Needs a current context.
std::string unsupportedSamples(uint32_t samples);

class Framebuffer {
public:
    Framebuffer() = default;
    ~Framebuffer();
    Framebuffer(Framebuffer&& other) noexcept;
    Framebuffer& operator=(Framebuffer&& other) noexcept;
    Framebuffer(const Framebuffer&) = delete;
    Framebuffer& operator=(const Framebuffer&) = delete;

    // False with a reason for a zero or oversized extent or an incomplete framebuffer.
    static bool create(const FramebufferDesc& desc, Framebuffer& out, std::string& error);

    // Binds for drawing and sets the viewport to the whole target.
    void bind() const;
    // Clears every colour attachment to `color` and depth to `depth` (0 for reversed-Z).
    void clear(float r, float g, float b, float a, float depth = 1.0f) const;
    // Clears one colour attachment, leaving the others and depth alone.
    void clearAttachment(uint32_t attachment, float r, float g, float b, float a) const;

    uint32_t width() const { return desc_.width; }
    uint32_t samples() const { return desc_.samples; }
    uint32_t height() const { return desc_.height; }
    uint32_t colorTexture(uint32_t attachment) const { return colors_.at(attachment); }
    uint32_t depthTexture() const { return depth_; }
    uint32_t id() const { return id_; }

    // Reads back an attachment as floats, top row first: colour as RGBA, depth as one channel
    // of window-space depth in [0, 1]. Waits for rendering to finish. An attachment that does
    // not exist gives an empty image. A multisampled colour attachment is resolved (averaged)
    // first; multisampled depth cannot be read back.
    Image readColor(uint32_t attachment = 0) const;
    Image readDepth() const;

private:
    void release();

    FramebufferDesc desc_;
    uint32_t id_ = 0;
    std::vector<uint32_t> colors_;
    uint32_t depth_ = 0;
};

} // namespace hexlod::render
