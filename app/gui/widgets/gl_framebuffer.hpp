#pragma once
// An off-screen colour + depth target in the current GL context, optionally multisampled, whose
// resolved colour is a texture: the 3D view draws into it and ImGui shows it as an image, and
// exports (screenshot of any size, replay frame sequences) read it back. Needs glad loaded.
#include "render/image.hpp"

namespace bhm::app::gui {

class GlFramebuffer {
  public:
    GlFramebuffer() = default;
    ~GlFramebuffer();
    GlFramebuffer(const GlFramebuffer&) = delete;
    GlFramebuffer& operator=(const GlFramebuffer&) = delete;

    //! (Re)creates the buffers when the size or sample count changed. Throws std::runtime_error
    //! when the driver refuses the size.
    void ensure(int width, int height, int samples);
    void bind_for_drawing();
    //! Resolves the samples into the texture (a no-op without multisampling).
    void resolve();
    //! Colour texture for ImGui::Image (bottom row first, as GL stores it); valid after resolve().
    unsigned texture() const { return texture_; }
    //! The framebuffer holding the resolved colour (for glBlitFramebuffer).
    unsigned read_framebuffer() const { return resolve_fbo_ ? resolve_fbo_ : draw_fbo_; }
    //! Reads the resolved colour, top row first, alpha 255.
    render::Image read_image();

    int width() const { return width_; }
    int height() const { return height_; }

  private:
    void release();
    int width_ = 0, height_ = 0, samples_ = 0;
    unsigned draw_fbo_ = 0, color_rb_ = 0, depth_rb_ = 0;
    unsigned resolve_fbo_ = 0, texture_ = 0;
};

}  // namespace bhm::app::gui
