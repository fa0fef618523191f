#pragma once
// An on-screen GLFW window with an OpenGL 3.3 core context (glad loaded), for the studio.
// Needs a display. GLFW is initialised by the first window and terminated with it, so keep
// one Window per process.
#include <string>

struct GLFWwindow;

namespace bhm::render {

class Window {
  public:
    //! Opens the window (multisampled when samples > 1). Throws std::runtime_error with GLFW's
    //! reason when there is no display or no suitable OpenGL.
    Window(int width, int height, const std::string& title, int samples = 4);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    GLFWwindow* handle() const { return window_; }
    //! Makes the context current (reloading glad's pointers if another context replaced them).
    void make_current();
    bool should_close() const;
    void poll_events();
    void swap_buffers();
    void set_vsync(bool on);
    //! Size of the drawable in pixels (differs from the window size on high-DPI screens).
    int framebuffer_width() const;
    int framebuffer_height() const;
    //! Binds the window's framebuffer for drawing.
    void bind();

  private:
    GLFWwindow* window_ = nullptr;
    void* loaded_clear_ = nullptr;  //!< a glad pointer as we loaded it, to notice other loaders
};

}  // namespace bhm::render
