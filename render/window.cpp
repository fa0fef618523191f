#include "render/window.hpp"

// glad must come before any other GL header.
#include <glad/gl.h>

#include <GLFW/glfw3.h>

#include <stdexcept>

namespace bhm::render {

namespace {
std::string last_glfw_error() {
    const char* description = nullptr;
    glfwGetError(&description);
    return description ? description : "unknown reason";
}
}  // namespace

Window::Window(int width, int height, const std::string& title, int samples) {
    if (!glfwInit()) throw std::runtime_error("GLFW: cannot initialise: " + last_glfw_error());
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_SAMPLES, samples > 1 ? samples : 0);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window_) {
        const std::string reason = last_glfw_error();
        glfwTerminate();
        throw std::runtime_error("GLFW: cannot open a " + std::to_string(width) + "x" +
                                 std::to_string(height) + " OpenGL 3.3 window: " + reason);
    }
    glfwMakeContextCurrent(window_);
    if (!gladLoadGL(reinterpret_cast<GLADloadfunc>(glfwGetProcAddress))) {
        glfwDestroyWindow(window_);
        glfwTerminate();
        throw std::runtime_error("GLFW: cannot load the OpenGL 3.3 functions");
    }
    loaded_clear_ = reinterpret_cast<void*>(glad_glClear);
    if (samples > 1) glEnable(GL_MULTISAMPLE);
}

Window::~Window() {
    if (window_) glfwDestroyWindow(window_);
    glfwTerminate();
}

void Window::make_current() {
    glfwMakeContextCurrent(window_);
    // glad's pointers are process-wide: an OSMesa target used in between leaves them pointing
    // into libOSMesa. Reload when ours were replaced.
    if (reinterpret_cast<void*>(glad_glClear) != loaded_clear_) {
        if (!gladLoadGL(reinterpret_cast<GLADloadfunc>(glfwGetProcAddress)))
            throw std::runtime_error("GLFW: cannot load the OpenGL 3.3 functions");
        loaded_clear_ = reinterpret_cast<void*>(glad_glClear);
    }
}
bool Window::should_close() const {
    return glfwWindowShouldClose(window_);
}
void Window::poll_events() {
    glfwPollEvents();
}
void Window::swap_buffers() {
    glfwSwapBuffers(window_);
}
void Window::set_vsync(bool on) {
    glfwSwapInterval(on ? 1 : 0);
}

int Window::framebuffer_width() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return w;
}

int Window::framebuffer_height() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return h;
}

void Window::bind() {
    make_current();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, framebuffer_width(), framebuffer_height());
}

}  // namespace bhm::render
