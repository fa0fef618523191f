#include "app/gui/widgets/gl_framebuffer.hpp"

#include <glad/gl.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace bhm::app::gui {

GlFramebuffer::~GlFramebuffer() {
    release();
}

void GlFramebuffer::release() {
    if (!draw_fbo_ && !texture_) return;
    // The context may already be gone at shutdown; glad's pointers are still valid then, and GL
    // ignores names it does not know.
    const GLuint fbos[] = {draw_fbo_, resolve_fbo_};
    const GLuint rbs[] = {color_rb_, depth_rb_};
    glDeleteFramebuffers(2, fbos);
    glDeleteRenderbuffers(2, rbs);
    glDeleteTextures(1, &texture_);
    draw_fbo_ = resolve_fbo_ = color_rb_ = depth_rb_ = texture_ = 0;
}

void GlFramebuffer::ensure(int width, int height, int samples) {
    width = std::max(1, width);
    height = std::max(1, height);
    GLint max_samples = 1, max_size = 0;
    glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
    samples = std::clamp(samples, 1, std::max(1, static_cast<int>(max_samples)));
    if (width == width_ && height == height_ && samples == samples_ && draw_fbo_) return;
    if (width > max_size || height > max_size)
        throw std::runtime_error("image size " + std::to_string(width) + "x" +
                                 std::to_string(height) + " exceeds the GL limit of " +
                                 std::to_string(max_size) + " pixels per side");
    release();
    width_ = width, height_ = height, samples_ = samples;

    glGenTextures(1, &texture_);
    glBindTexture(GL_TEXTURE_2D, texture_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);

    glGenFramebuffers(1, &draw_fbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, draw_fbo_);
    if (samples > 1) {
        glGenRenderbuffers(1, &color_rb_);
        glBindRenderbuffer(GL_RENDERBUFFER, color_rb_);
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width, height);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_rb_);
    } else {
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture_, 0);
    }
    glGenRenderbuffers(1, &depth_rb_);
    glBindRenderbuffer(GL_RENDERBUFFER, depth_rb_);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples > 1 ? samples : 0,
                                     GL_DEPTH_COMPONENT24, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_rb_);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("3D view framebuffer incomplete at " + std::to_string(width) +
                                 "x" + std::to_string(height));
    if (samples > 1) {
        glGenFramebuffers(1, &resolve_fbo_);
        glBindFramebuffer(GL_FRAMEBUFFER, resolve_fbo_);
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture_, 0);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw std::runtime_error("3D view resolve framebuffer incomplete");
    }
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
}

void GlFramebuffer::bind_for_drawing() {
    glBindFramebuffer(GL_FRAMEBUFFER, draw_fbo_);
}

void GlFramebuffer::resolve() {
    if (!resolve_fbo_) return;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, draw_fbo_);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_fbo_);
    glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT,
                      GL_NEAREST);
}

render::Image GlFramebuffer::read_image() {
    render::Image image(width_, height_);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, resolve_fbo_ ? resolve_fbo_ : draw_fbo_);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    std::vector<std::uint8_t> rows(image.rgba.size());
    glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    const std::size_t stride = static_cast<std::size_t>(width_) * 4;
    for (int y = 0; y < height_; ++y)  // GL is bottom-up; images are top-down
        std::copy_n(rows.data() + static_cast<std::size_t>(height_ - 1 - y) * stride, stride,
                    image.rgba.data() + static_cast<std::size_t>(y) * stride);
    for (std::size_t i = 3; i < image.rgba.size(); i += 4)
        image.rgba[i] = 255;
    return image;
}

}  // namespace bhm::app::gui
