// Framebuffer objects over textures, and their readback.
#include "hexlod/render/framebuffer.h"
#include "hexlod/render/gl_api.h"

#include <algorithm>
#include <cstdio>
#include <utility>

namespace hexlod::render {
namespace {

Image readAttachment(GLuint framebuffer, GLenum buffer, GLenum format, uint32_t channels, uint32_t width,
                     uint32_t height) {
    Image image(width, height, channels);
    gl::glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
    if (buffer != GL_NONE) gl::glNamedFramebufferReadBuffer(framebuffer, buffer);
    gl::glPixelStorei(GL_PACK_ALIGNMENT, 4);
    gl::glReadPixels(0, 0, GLsizei(width), GLsizei(height), format, GL_FLOAT, image.pixels.data());
    gl::glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    // GL's first row is the bottom one.
    size_t row = size_t(width) * channels;
    for (uint32_t y = 0; y < height / 2; ++y) {
        std::swap_ranges(image.pixels.begin() + y * row, image.pixels.begin() + (y + 1) * row,
                         image.pixels.begin() + (height - 1 - y) * row);
    }
    return image;
}

} // namespace

Framebuffer::~Framebuffer() {
    release();
}

Framebuffer::Framebuffer(Framebuffer&& other) noexcept
    : desc_(std::move(other.desc_)), id_(std::exchange(other.id_, 0)), colors_(std::move(other.colors_)),
      depth_(std::exchange(other.depth_, 0)) {}

Framebuffer& Framebuffer::operator=(Framebuffer&& other) noexcept {
    if (this != &other) {
        release();
        desc_ = std::move(other.desc_);
        id_ = std::exchange(other.id_, 0);
        colors_ = std::move(other.colors_);
        depth_ = std::exchange(other.depth_, 0);
    }
    return *this;
}

void Framebuffer::release() {
    if (id_) gl::glDeleteFramebuffers(1, &id_);
    if (!colors_.empty()) gl::glDeleteTextures(GLsizei(colors_.size()), colors_.data());
    if (depth_) gl::glDeleteTextures(1, &depth_);
    id_ = depth_ = 0;
    colors_.clear();
}

std::string unsupportedSamples(uint32_t samples) {
    GLint maxSamples = 1;
    gl::glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
    if (samples >= 1 && samples <= uint32_t(maxSamples)) return {};
    return std::to_string(samples) + " samples per pixel, this GL allows 1 to " + std::to_string(maxSamples);
}

bool Framebuffer::create(const FramebufferDesc& desc, Framebuffer& out, std::string& error) {
    GLint maxSize = 0, maxAttachments = 0;
    gl::glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    gl::glGetIntegerv(GL_MAX_COLOR_ATTACHMENTS, &maxAttachments);
    if (desc.width == 0 || desc.height == 0 || desc.width > uint32_t(maxSize) ||
        desc.height > uint32_t(maxSize)) {
        error = "framebuffer extent " + std::to_string(desc.width) + "x" + std::to_string(desc.height) +
                " is outside 1.." + std::to_string(maxSize);
        return false;
    }
    if (std::string why = unsupportedSamples(desc.samples); !why.empty()) {
        error = std::move(why);
        return false;
    }
    if (desc.colorFormats.size() > size_t(maxAttachments)) {
        error = std::to_string(desc.colorFormats.size()) + " colour attachments, at most " +
                std::to_string(maxAttachments);
        return false;
    }
    Framebuffer framebuffer;
    framebuffer.desc_ = desc;
    gl::glCreateFramebuffers(1, &framebuffer.id_);
    std::vector<GLenum> drawBuffers;
    const bool multisampled = desc.samples > 1;
    auto makeTexture = [&](uint32_t format) {
        GLuint texture = 0;
        if (multisampled) {
            gl::glCreateTextures(GL_TEXTURE_2D_MULTISAMPLE, 1, &texture);
            gl::glTextureStorage2DMultisample(texture, GLsizei(desc.samples), format, GLsizei(desc.width),
                                              GLsizei(desc.height), GL_TRUE);
        } else {
            gl::glCreateTextures(GL_TEXTURE_2D, 1, &texture);
            gl::glTextureStorage2D(texture, 1, format, GLsizei(desc.width), GLsizei(desc.height));
        }
        return texture;
    };
    for (uint32_t format : desc.colorFormats) {
        GLuint texture = makeTexture(format);
        if (!multisampled) {
            gl::glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
            gl::glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        }
        GLenum attachment = GL_COLOR_ATTACHMENT0 + GLenum(framebuffer.colors_.size());
        gl::glNamedFramebufferTexture(framebuffer.id_, attachment, texture, 0);
        framebuffer.colors_.push_back(texture);
        drawBuffers.push_back(attachment);
    }
    gl::glNamedFramebufferDrawBuffers(framebuffer.id_, GLsizei(drawBuffers.size()), drawBuffers.data());
    if (desc.depth) {
        framebuffer.depth_ = makeTexture(GL_DEPTH_COMPONENT32F);
        gl::glNamedFramebufferTexture(framebuffer.id_, GL_DEPTH_ATTACHMENT, framebuffer.depth_, 0);
    }
    GLenum status = gl::glCheckNamedFramebufferStatus(framebuffer.id_, GL_DRAW_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        char hex[16];
        std::snprintf(hex, sizeof hex, "0x%04x", unsigned(status));
        error = std::string("framebuffer incomplete (status ") + hex + ")";
        return false;
    }
    out = std::move(framebuffer);
    return true;
}

void Framebuffer::bind() const {
    gl::glBindFramebuffer(GL_DRAW_FRAMEBUFFER, id_);
    gl::glViewport(0, 0, GLsizei(desc_.width), GLsizei(desc_.height));
}

void Framebuffer::clear(float r, float g, float b, float a, float depth) const {
    const float color[4] = {r, g, b, a};
    for (size_t i = 0; i < colors_.size(); ++i) gl::glClearNamedFramebufferfv(id_, GL_COLOR, GLint(i), color);
    if (depth_) {
        gl::glClearNamedFramebufferfv(id_, GL_DEPTH, 0, &depth);
    }
}

void Framebuffer::clearAttachment(uint32_t attachment, float r, float g, float b, float a) const {
    const float color[4] = {r, g, b, a};
    if (attachment < colors_.size()) gl::glClearNamedFramebufferfv(id_, GL_COLOR, GLint(attachment), color);
}

Image Framebuffer::readColor(uint32_t attachment) const {
    if (attachment >= colors_.size()) return {};
    if (desc_.samples <= 1)
        return readAttachment(id_, GL_COLOR_ATTACHMENT0 + attachment, GL_RGBA, 4, desc_.width, desc_.height);
    // Resolve into a single-sample target of the attachment's format, then read that.
    Framebuffer resolved;
    std::string error;
    if (!create({desc_.width, desc_.height, {desc_.colorFormats[attachment]}, false, 1}, resolved, error))
        return {};
    gl::glNamedFramebufferReadBuffer(id_, GL_COLOR_ATTACHMENT0 + attachment);
    gl::glBlitNamedFramebuffer(id_, resolved.id_, 0, 0, GLint(desc_.width), GLint(desc_.height), 0, 0,
                               GLint(desc_.width), GLint(desc_.height), GL_COLOR_BUFFER_BIT, GL_NEAREST);
    return resolved.readColor(0);
}

Image Framebuffer::readDepth() const {
    if (desc_.samples > 1) return {};
    return readAttachment(id_, GL_NONE, GL_DEPTH_COMPONENT, 1, desc_.width, desc_.height);
}

} // namespace hexlod::render
