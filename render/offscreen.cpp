#include "render/offscreen.hpp"

// glad must come before any other GL header.
#include <glad/gl.h>

#include <GL/osmesa.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/gl_check.hpp"

namespace bhm::render {

struct OffscreenTarget::State {
    OSMesaContext context = nullptr;
    // OSMesa needs a buffer to make the context current; we draw into our own framebuffers,
    // so this one stays tiny.
    std::vector<unsigned char> osmesa_buffer = std::vector<unsigned char>(16 * 16 * 4);
    GLuint draw_fbo = 0, color_rb = 0, depth_rb = 0;
    GLuint resolve_fbo = 0, resolve_rb = 0;
    std::vector<std::uint8_t> scratch;

    // glad's function pointers are process-wide: a GLFW window loaded in between would leave
    // them pointing into libGL. We remember one of ours and reload when it changed.
    PFNGLCLEARPROC loaded_clear = nullptr;

    void make_current() {
        if (!OSMesaMakeCurrent(context, osmesa_buffer.data(), GL_UNSIGNED_BYTE, 16, 16))
            throw std::runtime_error("OSMesa: cannot make the off-screen context current");
        if (glad_glClear != loaded_clear || !loaded_clear) load_functions();
    }

    void load_functions() {
        if (!gladLoadGL(reinterpret_cast<GLADloadfunc>(OSMesaGetProcAddress)))
            throw std::runtime_error("OSMesa: cannot load the OpenGL 3.3 functions");
        loaded_clear = glad_glClear;
    }
};

OffscreenTarget::OffscreenTarget(int width, int height, int samples)
    : state_(std::make_unique<State>()) {
    if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
        throw std::runtime_error("off-screen target: size " + std::to_string(width) + "x" +
                                 std::to_string(height) + " is outside 1..16384");
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              24,
                              OSMESA_STENCIL_BITS,
                              0,
                              OSMESA_PROFILE,
                              OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION,
                              3,
                              OSMESA_CONTEXT_MINOR_VERSION,
                              3,
                              0};
    state_->context = OSMesaCreateContextAttribs(attributes, nullptr);
    if (!state_->context)
        throw std::runtime_error(
            "OSMesa: cannot create an OpenGL 3.3 core context (is libosmesa6 installed?)");
    try {
        state_->make_current();  // loads the GL functions too
    } catch (...) {
        OSMesaDestroyContext(state_->context);
        throw;
    }
    GLint max_samples = 1;
    glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
    samples_ = std::clamp(samples, 1, std::max(1, static_cast<int>(max_samples)));
    width_ = width;
    height_ = height;
    try {
        create_framebuffers();
    } catch (...) {
        OSMesaDestroyContext(state_->context);
        throw;
    }
}

OffscreenTarget::~OffscreenTarget() {
    if (!state_->context) return;
    state_->make_current();
    delete_framebuffers();
    // Release it first: GL calls made after this (other objects' destructors) then reach Mesa's
    // no-context stubs instead of a destroyed context.
    OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
    OSMesaDestroyContext(state_->context);
}

void OffscreenTarget::create_framebuffers() {
    State& s = *state_;
    glGenFramebuffers(1, &s.draw_fbo);
    glGenRenderbuffers(1, &s.color_rb);
    glGenRenderbuffers(1, &s.depth_rb);
    glBindFramebuffer(GL_FRAMEBUFFER, s.draw_fbo);
    glBindRenderbuffer(GL_RENDERBUFFER, s.color_rb);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples_ > 1 ? samples_ : 0, GL_RGBA8, width_,
                                     height_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, s.color_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, s.depth_rb);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples_ > 1 ? samples_ : 0,
                                     GL_DEPTH_COMPONENT24, width_, height_);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, s.depth_rb);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("off-screen target: framebuffer incomplete at " +
                                 std::to_string(width_) + "x" + std::to_string(height_));
    if (samples_ > 1) {
        glGenFramebuffers(1, &s.resolve_fbo);
        glGenRenderbuffers(1, &s.resolve_rb);
        glBindFramebuffer(GL_FRAMEBUFFER, s.resolve_fbo);
        glBindRenderbuffer(GL_RENDERBUFFER, s.resolve_rb);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width_, height_);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                  s.resolve_rb);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw std::runtime_error("off-screen target: resolve framebuffer incomplete");
    }
    glBindFramebuffer(GL_FRAMEBUFFER, s.draw_fbo);
    check_gl_error("creating the off-screen framebuffers");
}

void OffscreenTarget::delete_framebuffers() {
    State& s = *state_;
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    const GLuint fbos[] = {s.draw_fbo, s.resolve_fbo};
    const GLuint rbs[] = {s.color_rb, s.depth_rb, s.resolve_rb};
    glDeleteFramebuffers(2, fbos);
    glDeleteRenderbuffers(3, rbs);
    s.draw_fbo = s.resolve_fbo = s.color_rb = s.depth_rb = s.resolve_rb = 0;
}

void OffscreenTarget::bind() {
    state_->make_current();
    glBindFramebuffer(GL_FRAMEBUFFER, state_->draw_fbo);
    glViewport(0, 0, width_, height_);
}

void OffscreenTarget::resize(int width, int height) {
    if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
        throw std::runtime_error("off-screen target: size " + std::to_string(width) + "x" +
                                 std::to_string(height) + " is outside 1..16384");
    state_->make_current();
    delete_framebuffers();
    width_ = width;
    height_ = height;
    create_framebuffers();
}

Image OffscreenTarget::read_image() {
    Image image;
    read_image(image);
    return image;
}

void OffscreenTarget::read_image(Image& out) {
    State& s = *state_;
    state_->make_current();
    GLuint source = s.draw_fbo;
    if (samples_ > 1) {
        glBindFramebuffer(GL_READ_FRAMEBUFFER, s.draw_fbo);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, s.resolve_fbo);
        glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT,
                          GL_NEAREST);
        source = s.resolve_fbo;
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, source);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    const std::size_t row = static_cast<std::size_t>(width_) * 4;
    s.scratch.resize(row * static_cast<std::size_t>(height_));
    glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, s.scratch.data());
    glBindFramebuffer(GL_FRAMEBUFFER, s.draw_fbo);
    check_gl_error("reading the off-screen pixels");
    if (out.width != width_ || out.height != height_) out = Image(width_, height_);
    // GL rows run bottom-up; images top-down.
    for (int y = 0; y < height_; ++y) {
        const auto* src = s.scratch.data() + row * static_cast<std::size_t>(height_ - 1 - y);
        std::copy(
            src, src + row,
            out.rgba.begin() + static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(y)));
    }
    for (std::size_t i = 3; i < out.rgba.size(); i += 4)
        out.rgba[i] = 255;
}

std::string OffscreenTarget::gl_renderer() const {
    state_->make_current();
    const auto* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    return name ? name : "unknown";
}

}  // namespace bhm::render
